// Renders that survive being killed, in-process: the interrupt flag and its exit codes, the
// partial file's exact round trip of the film's sums, a render stopped after some tiles and
// resumed from its partial file equal bit for bit to one rendered in one go, and the memory
// budget's size parsing and refusal; a photon pass stops between blocks when interrupted.
#include <gtest/gtest.h>

#include <csignal>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/rng.h"
#include "film/partial_film.h"
#include "photon/photon_pass.h"
#include "render/renderer.h"
#include "scene/memory_budget.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace mirage;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool samePixel(const Film::Pixel& a, const Film::Pixel& b) {
    return sameBits(a.xyz[0], b.xyz[0]) && sameBits(a.xyz[1], b.xyz[1]) &&
           sameBits(a.xyz[2], b.xyz[2]) && sameBits(a.alpha, b.alpha) && a.samples == b.samples &&
           a.nonFinite == b.nonFinite && sameBits(a.xyzSq[0], b.xyzSq[0]) &&
           sameBits(a.xyzSq[1], b.xyzSq[1]) && sameBits(a.xyzSq[2], b.xyzSq[2]);
}

// A 1 m box of heterogeneous smoke under a sun: every pixel's value depends on its samples.
RenderScene smokeBox() {
    RenderScene scene;
    scene.media.push_back(test::gridMedium(
        [](int i, int j, int k) { return 0.5f + 0.5f * std::sin(0.4f * i + 0.3f * j + 0.2f * k); },
        0, 15, 1.0 / 16, 1.f, 4.f, 0.3f));
    scene.lights.push_back(makeDistantLight(Vec3(0.3f, -1, 0.2f), 470.f, Spectrum(1.f)));
    scene.camera.position = Vec3(0.5f, 0.5f, 3.f);
    scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
    return scene;
}

RenderSettings smallSettings() {
    RenderSettings s;
    s.width = 37;  // not a multiple of the tile size: clipped edge tiles
    s.height = 29;
    s.tileSize = 8;
    s.spp = 3;
    s.seed = 11;
    s.progress = Progress::Mode::Quiet;
    return s;
}

}  // namespace

TEST(Interrupt, SignalSetsTheFlagAndTheExitCodeIs128PlusTheSignal) {
    installInterruptHandlers();
    EXPECT_FALSE(interruptRequested());
    std::raise(SIGTERM);  // handled: the test process survives
    EXPECT_TRUE(interruptRequested());
    EXPECT_EQ(interruptSignal(), SIGTERM);
    EXPECT_EQ(interruptExitCode(), 143);
    resetInterruptHandlers();
    EXPECT_FALSE(interruptRequested());
    requestInterrupt(SIGINT);
    EXPECT_EQ(interruptExitCode(), 130);
    clearInterrupt();
    EXPECT_EQ(interruptExitCode(), 0);
}

TEST(PartialFilm, RoundTripsTheSumsOfFinishedTilesBitForBit) {
    const int w = 21, h = 13, tile = 8;  // 3 × 2 tiles, the last column and row clipped
    Film film(w, h);
    Sampler rng(5, 0, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Film::Pixel& p = film.pixel(x, y);
            for (double& c : p.xyz) c = rng.get1Dd() * 1e3 - 10.0;  // full 53-bit mantissas
            p.alpha = rng.get1Dd();
            p.samples = uint32_t(rng.get1D() * 1e6f);
            p.nonFinite = x + y;
        }
    std::vector<uint8_t> done = {1, 0, 1, 0, 1, 1};
    const std::string path = test::tempDir() + "/frame.exr.partial";
    writePartialFilm(path, film, tile, done, Mat3(), {{"fingerprint", "abc123"}});

    PartialFilm back = readPartialFilm(path);
    ASSERT_TRUE(back.film);
    EXPECT_EQ(back.tileSize, tile);
    EXPECT_EQ(back.done, done);
    EXPECT_EQ(back.metadata["fingerprint"], "abc123");
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool finished = done[size_t(y / tile) * 3 + x / tile];
            const Film::Pixel& b = back.film->pixel(x, y);
            if (finished)
                EXPECT_TRUE(samePixel(b, film.pixel(x, y))) << x << "," << y;
            else
                EXPECT_EQ(b.samples, 0u) << "an unfinished tile must stay empty";
        }
}

TEST(PartialFilm, AnExrThatIsNotAPartialFileIsRefused) {
    const std::string dir = test::tempDir();
    Film film(4, 4);
    writePartialFilm(dir + "/a.partial", film, 4, {1}, Mat3(), {});
    std::filesystem::rename(dir + "/a.partial", dir + "/a.exr");
    // A real partial file under another name still reads; garbage does not.
    EXPECT_NO_THROW(readPartialFilm(dir + "/a.exr"));
    {
        FILE* f = std::fopen((dir + "/b.partial").c_str(), "w");
        std::fputs("not an exr", f);
        std::fclose(f);
    }
    EXPECT_THROW(readPartialFilm(dir + "/b.partial"), MirageError);
}

TEST(Renderer, ResumedRenderEqualsOneRenderedInOneGoBitForBit) {
    RenderScene scene = smokeBox();
    RenderSettings s = smallSettings();
    auto integrator = makeSingleScatterIntegrator();
    integrator->preprocess(scene);

    RenderStats full;
    Film reference = render(scene, *integrator, s, &full);
    EXPECT_FALSE(full.interrupted);

    // Stop after 7 tiles (the flag is raised as by SIGINT; tiles in flight finish) and keep the
    // finished ones through a partial file, as a killed `mirage render` does.
    TileCheckpoint first;
    first.stopAfterTiles = 7;
    RenderStats st1;
    Film part = render(scene, *integrator, s, &st1, &first);
    EXPECT_TRUE(st1.interrupted);
    EXPECT_EQ(interruptSignal(), SIGINT);
    clearInterrupt();
    EXPECT_GE(st1.tilesDone, 7);
    EXPECT_LT(st1.tilesDone, st1.tiles);
    const std::string path = test::tempDir() + "/f.exr.partial";
    writePartialFilm(path, part, s.tileSize, first.done, Mat3(), {});

    PartialFilm saved = readPartialFilm(path);
    TileCheckpoint second;
    second.initial = saved.film.get();
    second.done = saved.done;
    RenderStats st2;
    Film resumed = render(scene, *integrator, s, &st2, &second);
    EXPECT_FALSE(st2.interrupted);
    EXPECT_EQ(st2.tilesResumed, st1.tilesDone);
    EXPECT_EQ(st2.tilesDone, st2.tiles);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x)
            ASSERT_TRUE(samePixel(resumed.pixel(x, y), reference.pixel(x, y))) << x << "," << y;
}

TEST(Renderer, TileFinishedIsCalledWithFinishedTilesAndEndsWithAllDone) {
    RenderScene scene = smokeBox();
    RenderSettings s = smallSettings();
    auto integrator = makeSingleScatterIntegrator();
    integrator->preprocess(scene);
    TileCheckpoint cp;
    int calls = 0, maxDone = 0;
    cp.tileFinished = [&](const Film&, const std::vector<uint8_t>& done) {
        ++calls;
        int n = 0;
        for (uint8_t d : done) n += d;
        EXPECT_GE(n, 1);
        maxDone = std::max(maxDone, n);
    };
    RenderStats st;
    render(scene, *integrator, s, &st, &cp);
    EXPECT_GE(calls, 1);
    EXPECT_LE(calls, st.tiles);
    EXPECT_LE(maxDone, st.tiles);
    for (uint8_t d : cp.done) EXPECT_EQ(d, 1);
}

TEST(MemoryBudget, ParsesSizesWithBinaryMultiples) {
    EXPECT_EQ(parseMemorySize("4G"), 4ull << 30);
    EXPECT_EQ(parseMemorySize("512M"), 512ull << 20);
    EXPECT_EQ(parseMemorySize("1.5G"), 3ull << 29);
    EXPECT_EQ(parseMemorySize("64k"), 64ull << 10);
    EXPECT_EQ(parseMemorySize("2GiB"), 2ull << 30);
    EXPECT_EQ(parseMemorySize("1000"), 1000ull);
    for (const char* bad : {"", "G", "4X", "-1G", "0", "nanG", "1e30T"})
        EXPECT_THROW(parseMemorySize(bad), MirageError) << bad;
}

TEST(MemoryBudget, RefusesAnEstimateOverBudgetNamingWhatDominates) {
    MemoryEstimate e;
    e.items = {{"grids", 100ull << 20}, {"photon maps", 3ull << 30}, {"film", 1ull << 20}};
    EXPECT_NO_THROW(checkMemoryBudget(e, 4ull << 30, "s.toml"));
    try {
        checkMemoryBudget(e, 1ull << 30, "s.toml");
        FAIL() << "expected a refusal";
    } catch (const MirageError& err) {
        std::string m = err.what();
        EXPECT_NE(m.find("s.toml"), std::string::npos) << m;
        // Largest first: the photon maps lead the breakdown.
        EXPECT_LT(m.find("photon maps"), m.find("grids")) << m;
        EXPECT_NE(m.find("1.00 GiB"), std::string::npos) << m;
    }
    EXPECT_GT(currentMemoryBytes(), 0u);
}

// The passes' sums, their developed layers and deep samples are memory per pixel the film
// estimate alone leaves out: each adds its known bytes per pixel.
TEST(MemoryBudget, PassesAndDeepSamplesRaiseTheEstimateByTheirBytesPerPixel) {
    Scene scene;
    scene.settings.width = 40;
    scene.settings.height = 30;
    const uint64_t pixels = 40 * 30;
    auto bytesOf = [&](const std::string& prefix) {
        uint64_t bytes = 0;
        for (const MemoryItem& i : estimateFrameMemory(scene, "single").items)
            if (i.what.rfind(prefix, 0) == 0) bytes += i.bytes;
        return bytes;
    };
    EXPECT_EQ(bytesOf("film"), pixels * kBytesPerPixel);
    EXPECT_EQ(bytesOf("passes"), 0u);
    EXPECT_EQ(bytesOf("deep"), 0u);

    scene.render.cryptoObjects.volumes = {"fire", "fog"};
    scene.settings.aovs = {"volume_direct", "depth", "crypto_volume"};
    // Sums: 3 (XYZ) + 2 (depth and its count) + 2 (one coverage per volume) doubles, each kept
    // by the film, the partial file's record and a resumed copy (8 + 8 + 8 B); channels: 3 + 1
    // + 12 (three RGBA rank layers) floats, each developed and copied for output (4 + 4 B).
    EXPECT_EQ(bytesOf("passes"), pixels * (7 * 24 + 16 * 8));
    EXPECT_EQ(bytesOf("film"), pixels * kBytesPerPixel);

    // Deep output: each pixel's list (24 B) and 32 planned samples of 24 B.
    scene.settings.deep.path = "deep.exr";
    EXPECT_EQ(bytesOf("deep"), pixels * (24 + 32 * 24));
}

TEST(Interrupt, PhotonPassStopsBetweenBlocks) {
    // Ctrl-C during a long photon pass: the remaining blocks are skipped, so the pass returns
    // at once with the flag recorded, instead of tracing every photon first.
    RenderScene scene = smokeBox();
    std::vector<const Light*> lights{scene.lights[0].get()};
    std::vector<const Medium*> media{scene.media[0].get()};
    PhotonPassSettings ps;
    ps.photons = 200000;
    ps.seed = 3;
    ps.progress = Progress::Mode::Quiet;
    PhotonPassStats full, stopped;
    PhotonList all = tracePhotons(lights, media, ps, &full);
    EXPECT_FALSE(full.interrupted);
    ASSERT_GT(all.size(), 1000u);
    requestInterrupt(SIGINT);
    PhotonList none = tracePhotons(lights, media, ps, &stopped);
    clearInterrupt();
    EXPECT_TRUE(stopped.interrupted);
    EXPECT_TRUE(none.empty());  // the flag was up before the first block
}
