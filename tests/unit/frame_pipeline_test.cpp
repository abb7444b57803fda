// The frame pipeline as a library (src/frame/), what the Python module calls: a frame request
// built in code, loaded, rendered and written, gives the pixels and the header of `mirage
// render` with the same settings; the header and the output image it returns are those the EXR
// holds; a cancel token stops a render between tiles, its finished tiles whole, and a render in
// passes with its whole passes, without touching the process's signal flag; the request's own
// checks, file names, integrator and --skip-existing.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <csignal>
#include <cstring>
#include <map>

#include "core/cancel.h"
#include "core/error.h"
#include "film/color.h"
#include "film/image_io.h"
#include "frame/frame_load.h"
#include "frame/frame_output.h"
#include "frame/frame_prefetch.h"
#include "frame/render_frame.h"
#include "test_support.h"

using namespace mirage;

namespace {

// A fog sphere of 24×24 pixels, 2 samples of the path tracer, written to `out`, quietly.
FrameRequest fogRequest(const std::string& dir, const std::string& out) {
    FrameRequest r;
    r.input = test::writeFogSphereScene(dir, "resolution = [24, 24]\nspp = 2\n",
                                        "integrator = \"volpath\"\n");
    r.output = out;
    r.quiet = true;
    return r;
}

// A header without the keys that measure wall time, and the time it was written.
std::map<std::string, std::string> untimed(std::map<std::string, std::string> m) {
    for (auto it = m.begin(); it != m.end();) {
        const std::string& k = it->first;
        const bool timed = k.find("seconds") != std::string::npos || k == "mirage:time_spent" ||
                           k == "mirage:photons_per_second" || k == "DateTime";
        it = timed ? m.erase(it) : std::next(it);
    }
    return m;
}

// The frame rendered in code and written to request.output: its header.
ExrOptions renderInCode(const FrameRequest& request, const ColorPipeline& color) {
    std::optional<LoadedFrame> frame = loadFrame(request, color);
    EXPECT_TRUE(frame);
    RenderedFrame rendered = renderFrame(frame->scene, color);
    EXPECT_FALSE(rendered.stats.interrupted);
    return writeFrame(*frame, rendered, color);
}

bool sameImage(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height || a.rgba != b.rgba ||
        a.layers.size() != b.layers.size())
        return false;
    for (size_t i = 0; i < a.layers.size(); ++i)
        if (a.layers[i].name != b.layers[i].name || a.layers[i].pixels != b.layers[i].pixels)
            return false;
    return true;
}

bool samePixel(const Film::Pixel& p, const Film::Pixel& q) {
    return std::memcmp(p.xyz, q.xyz, sizeof p.xyz) == 0 && p.samples == q.samples;
}

}  // namespace

// Three requests and their command lines: one render, a render in passes with a pass, the photon
// mapper with its statistics in the header.
TEST(FramePipeline, ARequestRenderedInCodeIsTheCommandsFrame) {
    struct Case {
        std::string args;
        void (*set)(FrameRequest*);
    };
    const Case cases[] = {
        {"", [](FrameRequest*) {}},
        {"--passes 3 --aov alpha",
         [](FrameRequest* r) {
             r->passes = 3;
             r->aovs = {"alpha"};
         }},
        {"--integrator photon --set render.photons=5000",
         [](FrameRequest* r) {
             r->integrator = "photon";
             r->overrides = {"render.photons=5000"};
         }},
    };
    const ColorPipeline color;
    for (const Case& c : cases) {
        const std::string dir = test::tempDir();
        FrameRequest request = fogRequest(dir, dir + "/code.exr");
        c.set(&request);
        const ExrOptions header = renderInCode(request, color);
        const auto cli = test::renderMetadata(request.input, c.args, dir + "/cli.exr");
        std::map<std::string, std::string> code;
        const Image codeImage = readExr(dir + "/code.exr", &code);
        EXPECT_TRUE(sameImage(codeImage, readExr(dir + "/cli.exr"))) << c.args;
        EXPECT_EQ(untimed(code), untimed(cli)) << c.args;
        // The header writeFrame returns is the one in the file.
        std::map<std::string, std::string> returned;
        for (const auto& [key, value] : header.metadata) returned["mirage:" + key] = value;
        for (const auto& [key, value] : untimed(returned)) EXPECT_EQ(code[key], value) << key;
        EXPECT_EQ(code["mirage:colorSpace"], header.colorSpace);
    }
}

// outputImage is what the EXR holds, in the scene's output colour space.
TEST(FramePipeline, TheOutputImageIsTheImageTheExrHolds) {
    const std::string dir = test::tempDir();
    FrameRequest request = fogRequest(dir, dir + "/frame.exr");
    request.overrides = {"output.color_space=\"Linear Rec.709 (sRGB)\""};
    request.aovs = {"albedo"};
    request.floatExr = true;
    const ColorPipeline color;
    const LoadedFrame frame = *loadFrame(request, color);
    RenderedFrame rendered = renderFrame(frame.scene, color);
    const Image image = outputImage(frame, rendered, color);
    EXPECT_NE(image.rgba, rendered.image.rgba);  // converted out of the working space
    const ExrOptions header = writeFrame(frame, rendered, color);
    EXPECT_EQ(header.colorSpace, "Linear Rec.709 (sRGB)");
    EXPECT_TRUE(sameImage(image, readExr(frame.out)));
}

// A cancel after the first tile: the tiles in flight finish, no other starts; each finished
// tile holds the pixels of the whole render, the others none, and no signal was raised.
TEST(FramePipeline, ACancelStopsARenderBetweenTiles) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    const std::string dir = test::tempDir();
    FrameRequest request = fogRequest(dir, dir + "/frame.exr");
    request.resolution = "32x32";
    request.overrides = {"film.tile_size=8"};
    const ColorPipeline color;
    const LoadedFrame frame = *loadFrame(request, color);
    const RenderedFrame whole = renderFrame(frame.scene, color);

    CancelToken cancel;
    TileCheckpoint tiles;
    tiles.tileFinished = [&](const Film&, const std::vector<uint8_t>&) { cancel.cancel(); };
    const RenderedFrame cut = renderFrame(frame.scene, color, {&tiles, nullptr, &cancel});
    EXPECT_TRUE(cut.stats.interrupted);
    EXPECT_EQ(cut.stats.tiles, 16);
    EXPECT_GE(cut.stats.tilesDone, 1);  // the first, and those in flight on the other thread
    EXPECT_LT(cut.stats.tilesDone, 16);
    EXPECT_FALSE(interruptRequested());
    for (int t = 0; t < 16; ++t)
        for (int y = (t / 4) * 8; y < (t / 4 + 1) * 8; ++y)
            for (int x = (t % 4) * 8; x < (t % 4 + 1) * 8; ++x) {
                const Film::Pixel& p = cut.film->pixel(x, y);
                if (tiles.done[size_t(t)])
                    EXPECT_TRUE(samePixel(p, whole.film->pixel(x, y))) << x << "," << y;
                else
                    EXPECT_EQ(p.samples, 0u) << x << "," << y;
            }
}

// A cancel after the second of five passes: the render stops there, and its film is the two
// passes that --passes 2 renders.
TEST(FramePipeline, ACancelledRenderInPassesKeepsItsWholePasses) {
    const std::string dir = test::tempDir();
    FrameRequest request = fogRequest(dir, dir + "/frame.exr");
    request.passes = 5;
    const ColorPipeline color;
    CancelToken cancel;
    PassCheckpoint passes;
    passes.passFinished = [&](const Film&, int done, double) {
        if (done == 2) cancel.cancel();
    };
    const RenderedFrame cut =
        renderFrame(loadFrame(request, color)->scene, color, {nullptr, &passes, &cancel});
    ASSERT_TRUE(cut.passes);
    EXPECT_TRUE(cut.stats.interrupted);
    EXPECT_EQ(cut.passes->passes, 2);
    EXPECT_EQ(cut.passes->stop, "interrupted");
    EXPECT_FALSE(interruptRequested());
    request.passes = 2;
    const RenderedFrame two = renderFrame(loadFrame(request, color)->scene, color);
    EXPECT_TRUE(test::sameFilm(*cut.film, *two.film));
}

// A program's token ignores SIGINT and SIGTERM unless it asks to follow them, as the command
// line's does; raising it leaves the process's flag alone.
TEST(CancelToken, FollowsTheSignalsOnlyWhenAsked) {
    CancelToken own, cli(CancelToken::Signals::Follow);
    EXPECT_FALSE(own.requested());
    EXPECT_FALSE(cli.requested());
    requestInterrupt(SIGINT);
    EXPECT_FALSE(own.requested());
    EXPECT_TRUE(cli.requested());
    EXPECT_TRUE(stopRequested(nullptr));
    EXPECT_FALSE(stopRequested(&own));
    clearInterrupt();
    own.cancel();
    EXPECT_TRUE(stopRequested(&own));
    EXPECT_FALSE(interruptRequested());
    own.reset();
    EXPECT_FALSE(own.requested());
}

// What CLI11 refuses on the command line, the request refuses in code.
TEST(FrameRequest, RefusesWhatTheCommandLineRefuses) {
    FrameRequest ok;
    ok.input = "scene.toml";
    EXPECT_NO_THROW(checkFrameRequest(ok));
    const std::vector<void (*)(FrameRequest*)> bad = {
        [](FrameRequest* r) { r->input.clear(); },
        [](FrameRequest* r) { r->spp = -1; },
        [](FrameRequest* r) { r->spp = (1 << 20) + 1; },
        [](FrameRequest* r) { r->turntable = -2; },
        [](FrameRequest* r) { r->timeLimit = 1e-4; },
        [](FrameRequest* r) { r->noiseThreshold = 11; },
        [](FrameRequest* r) { r->shutter = 2.5; },
        [](FrameRequest* r) {
            r->motionBlur = true;
            r->shutter = 0.5;
        },
        [](FrameRequest* r) {
            r->coarseSpp = 2;
            r->passes = 3;
        },
        [](FrameRequest* r) {
            r->region = "0,0,8,8";
            r->timeLimit = 1;
        },
    };
    for (size_t i = 0; i < bad.size(); ++i) {
        FrameRequest r = ok;
        bad[i](&r);
        EXPECT_THROW(checkFrameRequest(r), MirageError) << "case " << i;
    }
}

TEST(FrameRequest, NamesTheFramesFiles) {
    EXPECT_EQ(framePath("out/a.exr", 7, false), "out/a.exr");
    EXPECT_EQ(framePath("out/a.exr", 7, true), "out/a.0007.exr");
    EXPECT_EQ(framePath("out/a.$F4.exr", 7, false), "out/a.0007.exr");
    EXPECT_EQ(framePath("out/a.####.exr", 12, true), "out/a.0012.exr");
}

// The integrator is resolved once, by the loader, with the request's name: "auto" chooses and
// says why; a named one is taken as named.
TEST(FrameRequest, TheIntegratorIsResolvedOnceWhenTheFrameLoads) {
    const std::string dir = test::tempDir();
    const ColorPipeline color;
    FrameRequest request = fogRequest(dir, dir + "/frame.exr");
    request.integrator = "auto";
    const LoadedFrame chosen = *loadFrame(request, color);
    EXPECT_NE(chosen.scene.integrator, "auto");
    EXPECT_EQ(chosen.scene.integratorWhy.rfind("auto: ", 0), 0u) << chosen.scene.integratorWhy;
    request.integrator = "single";
    const LoadedFrame named = *loadFrame(request, color);
    EXPECT_EQ(named.scene.integrator, "single");
    EXPECT_TRUE(named.scene.integratorWhy.empty());
}

// --skip-existing: a finished frame is not loaded again.
TEST(FrameRequest, AFinishedFrameIsSkipped) {
    const std::string dir = test::tempDir();
    const ColorPipeline color;
    FrameRequest request = fogRequest(dir, dir + "/frame.exr");
    request.skipExisting = true;
    ASSERT_TRUE(loadFrame(request, color));
    renderInCode(request, color);
    EXPECT_FALSE(loadFrame(request, color));
    request.output.clear();  // known only once loaded: the scene's [output] path
    request.overrides = {"output.path=\"" + dir + "/frame.exr\""};
    EXPECT_FALSE(loadFrame(request, color));
}

// A sequence's next frame loads while the current one renders (frame/frame_prefetch.h): the
// frame it gives renders to the same bits as one loaded in turn, its load's error comes out
// when it is taken, and a memory budget, a last frame or too little free memory turns it off.
TEST(FramePrefetch, APrefetchedFrameIsTheFrameLoadedInTurn) {
    const std::string dir = test::tempDir();
    const ColorPipeline color;
    FramePrefetch next;
    FrameRequest request = fogRequest(dir, dir + "/early.exr");
    next.start(request, color);
    EXPECT_TRUE(next.holds(request.frame));
    EXPECT_FALSE(next.holds(request.frame + 1));
    std::optional<LoadedFrame> early = next.take();
    ASSERT_TRUE(early);
    EXPECT_TRUE(early->prefetched);
    RenderedFrame rendered = renderFrame(early->scene, color);
    writeFrame(*early, rendered, color);
    request.output = dir + "/in_turn.exr";
    renderInCode(request, color);
    EXPECT_TRUE(sameImage(readExr(dir + "/early.exr"), readExr(dir + "/in_turn.exr")));

    request.input = dir + "/missing.toml";
    next.start(request, color);
    try {
        next.take();
        ADD_FAILURE() << "a missing scene loaded";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.toml"), std::string::npos) << e.what();
    }

    const uint64_t GiB = uint64_t(1) << 30;
    EXPECT_TRUE(prefetchesFrames(request, 1, 4 * GiB, 6 * GiB));
    EXPECT_FALSE(prefetchesFrames(request, 0, 4 * GiB, 6 * GiB));  // the last frame
    EXPECT_FALSE(prefetchesFrames(request, 1, 4 * GiB, 5 * GiB));  // two frames would not fit
    request.memoryBudget = GiB;
    EXPECT_FALSE(prefetchesFrames(request, 1, 4 * GiB, 6 * GiB));
}

// `mirage render` over a sequence says which frames were read during the frame before.
TEST(FramePrefetch, TheCommandReadsTheNextFrameDuringARender) {
    const std::string dir = test::tempDir();
    const std::string scene = fogRequest(dir, "").input;
    std::string log;
    ASSERT_EQ(0, test::runMirage("render '" + scene + "' -o '" + dir +
                                     "/seq.####.exr' "
                                     "--frames 1-2",
                                 &log))
        << log;
    const std::string prefetched = "(while the frame before rendered)";
    const size_t frame2 = log.find("frame 2: 24x24");
    ASSERT_NE(frame2, std::string::npos) << log;
    EXPECT_EQ(log.find(prefetched), log.find(prefetched, frame2)) << log;  // frame 2's alone
    EXPECT_NE(log.find(prefetched), std::string::npos) << log;
    ASSERT_EQ(0, test::runMirage("render '" + scene + "' -o '" + dir +
                                     "/seq.####.exr' "
                                     "--frames 1-2 --max-memory 8G",
                                 &log))
        << log;
    EXPECT_EQ(log.find(prefetched), std::string::npos) << log;
}
