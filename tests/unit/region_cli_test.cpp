// Regions of a frame end to end (mirage render --region, mirage assemble): a region's pixels are
// the same bits as those pixels of a whole-frame render on 1 and on 2 threads (under a sky with
// a sun too, whose shade volpath lays over the media per frame); its EXR's data
// window is the region and its display window the frame; a killed region resumes to the same
// bits; regions assemble into the frame bit for bit, and assembly refuses missing, overlapping
// and foreign regions with a message naming them.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

// The procedural fog sphere, 40×24 pixels in 8-pixel tiles, photon integrator (its photon pass
// runs in every region and must give the same photons).
std::string writeScene(const std::string& dir) {
    return test::writeFogSphereScene(dir, "resolution = [40, 24]\ntile_size = 8\nspp = 2\nseed = 3",
                                     "integrator = \"photon\"\nphotons = 5000");
}

int mirage(const std::string& args, std::string* out, const std::string& env = "") {
    return test::runCommand(env + " '" + test::mirageBinary() + "' " + args, out);
}

// Every channel of an EXR as float, with its data and display windows.
struct Exr {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;
    float at(int x, int y, int c) const {  // x, y in frame pixels
        return pixels[(size_t(y - spec.y) * spec.width + (x - spec.x)) * spec.nchannels + c];
    }
};

Exr readAll(const std::string& path) {
    Exr e;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return e;
    e.spec = in->spec();
    e.pixels.resize(size_t(e.spec.width) * e.spec.height * e.spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, e.spec.nchannels, OIIO::TypeFloat, e.pixels.data()));
    return e;
}

// How many values of the region differ from the same pixels of the frame (bitwise: == on the
// floats, no NaN in these renders).
size_t differences(const Exr& region, const Exr& frame) {
    size_t n = 0;
    for (int y = region.spec.y; y < region.spec.y + region.spec.height; ++y)
        for (int x = region.spec.x; x < region.spec.x + region.spec.width; ++x)
            for (int c = 0; c < region.spec.nchannels; ++c)
                n += region.at(x, y, c) != frame.at(x, y, c);
    return n;
}

}  // namespace

TEST(RegionCli, RegionPixelsAreTheFullRendersBitsOnOneAndTwoThreads) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    ASSERT_EQ(mirage("render '" + scene + "' -q --float -o '" + dir + "/full.exr'", &out), 0)
        << out;
    const Exr full = readAll(dir + "/full.exr");
    // A region that cuts through the 8-pixel tiles on every side.
    for (int threads : {1, 2}) {
        const std::string path = dir + "/region" + std::to_string(threads) + ".exr";
        ASSERT_EQ(mirage("render '" + scene + "' -q --float --region 5,3,27,19 --threads " +
                             std::to_string(threads) + " -o '" + path + "'",
                         &out),
                  0)
            << out;
        const Exr region = readAll(path);
        EXPECT_EQ(region.spec.x, 5);
        EXPECT_EQ(region.spec.y, 3);
        EXPECT_EQ(region.spec.width, 22);
        EXPECT_EQ(region.spec.height, 16);
        EXPECT_EQ(region.spec.full_width, 40);
        EXPECT_EQ(region.spec.full_height, 24);
        EXPECT_EQ(region.spec.get_string_attribute("mirage:region"), "5,3,27,19");
        EXPECT_EQ(region.spec.get_string_attribute("mirage:fingerprint"),
                  full.spec.get_string_attribute("mirage:fingerprint"));
        EXPECT_EQ(differences(region, full), 0u) << threads << " thread(s)";
    }
}

// Under a sky map with a sun, volpath's vertices draw the sky at a rate from the sun's shade, a
// grid laid over the media with the frame (render/sun_shade.h): a region builds the same grid,
// so its pixels are still the frame's bits.
TEST(RegionCli, ARegionUnderASkyWithASunIsTheFullRendersBits) {
    const std::string dir = test::tempDir();
    test::writeSunnySky(dir);
    const std::string scene = test::writeFogSphereScene(
        dir, "resolution = [40, 24]\ntile_size = 8\nspp = 2\nseed = 3", "integrator = \"volpath\"",
        "type = \"dome\"\nmap = \"sunny.hdr\"");
    std::string out;
    ASSERT_EQ(mirage("info '" + scene + "'", &out), 0) << out;
    EXPECT_NE(out.find("at a rate from the sun's optical depth"), std::string::npos) << out;
    ASSERT_EQ(mirage("render '" + scene + "' -q --float -o '" + dir + "/full.exr'", &out), 0)
        << out;
    const std::string path = dir + "/region.exr";
    ASSERT_EQ(
        mirage("render '" + scene + "' -q --float --region 5,3,27,19 --threads 2 -o '" + path + "'",
               &out),
        0)
        << out;
    const Exr full = readAll(dir + "/full.exr"), region = readAll(path);
    EXPECT_GT(full.at(20, 12, 3), 0.f) << "the sphere is not in the frame";
    EXPECT_EQ(differences(region, full), 0u);
}

TEST(RegionCli, AKilledRegionResumesToTheSameBits) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    ASSERT_EQ(mirage("render '" + scene + "' -q --float -o '" + dir + "/full.exr'", &out), 0)
        << out;
    const std::string target = dir + "/region.exr";
    const std::string args = "render '" + scene + "' -q --float --region 8,0,40,17 -o '" + target +
                             "' --set film.tile_size=4";
    ASSERT_EQ(mirage(args + " --threads 2", &out, "MIRAGE_TEST_STOP_AFTER_TILES=3"), 130) << out;
    ASSERT_TRUE(fs::exists(target + ".partial")) << out;
    // A partial file of another region is refused.
    EXPECT_EQ(mirage("render '" + scene + "' -q --float --region 0,0,40,17 --resume -o '" + target +
                         "' --set film.tile_size=4",
                     &out),
              1);
    EXPECT_NE(out.find("region was '8,0,40,17', now '0,0,40,17'"), std::string::npos) << out;
    ASSERT_EQ(mirage(args + " --resume --threads 1", &out), 0) << out;
    const Exr region = readAll(target);
    EXPECT_GE(std::stoi(region.spec.get_string_attribute("mirage:resumed_tiles")), 3);
    // tile_size is part of the fingerprint, not of the pixels: compare to the full render.
    EXPECT_EQ(differences(region, readAll(dir + "/full.exr")), 0u);
}

TEST(RegionCli, ARegionOutsideTheFrameIsOneClearError) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --region 0,0,41,10 -o '" + dir + "/r.exr'", &out),
              1);
    EXPECT_NE(out.find("--region '0,0,41,10': expected 0 ≤ X0 < X1 ≤ 40"), std::string::npos)
        << out;
    EXPECT_NE(out.find("the frame is 40x24"), std::string::npos) << out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --region 4,4,2 -o '" + dir + "/r.exr'", &out), 1);
    EXPECT_NE(out.find("expected X0,Y0,X1,Y1"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir + "/r.exr"));
}

// What a region cannot be combined with: a stop that reads the image (its pass count would be
// the region's, not the frame's: a syntax error, exit 2) and deep output (merged per pixel of
// the whole frame: one clear error, exit 1). A region in a fixed number of passes is the same
// bits as those pixels of the whole frame in as many passes.
TEST(RegionCli, RegionsRefuseImageDrivenStopsAndDeepButTakeFixedPasses) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    EXPECT_EQ(
        mirage("render '" + scene + "' -q --region 0,0,8,8 --time-limit 5 -o '" + dir + "/r.exr'",
               &out),
        2)
        << out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --region 0,0,8,8 --noise-threshold 0.1 -o '" + dir +
                         "/r.exr'",
                     &out),
              2)
        << out;
    EXPECT_EQ(mirage("render '" + scene + "' -q --region 0,0,8,8 --deep '" + dir + "/d.exr' -o '" +
                         dir + "/r.exr'",
                     &out),
              1)
        << out;
    EXPECT_NE(out.find("covers the whole frame"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir + "/r.exr"));

    ASSERT_EQ(mirage("render '" + scene + "' -q --float --passes 2 -o '" + dir + "/f.exr'", &out),
              0)
        << out;
    ASSERT_EQ(mirage("render '" + scene + "' -q --float --passes 2 --region 8,8,24,16 -o '" + dir +
                         "/r.exr'",
                     &out),
              0)
        << out;
    const Exr region = readAll(dir + "/r.exr"), frame = readAll(dir + "/f.exr");
    EXPECT_EQ(region.spec.x, 8);
    EXPECT_EQ(region.spec.width, 16);
    EXPECT_EQ(differences(region, frame), 0u);
}

TEST(AssembleCli, FourRegionsAssembleIntoTheFullRenderBitForBit) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    // Half EXRs, as a farm writes them: assembly must not round through another type.
    ASSERT_EQ(mirage("render '" + scene + "' -q -o '" + dir + "/full.exr'", &out), 0) << out;
    const char* regions[] = {"0,0,17,11", "17,0,40,11", "0,11,17,24", "17,11,40,24"};
    std::string tiles;
    for (int i = 0; i < 4; ++i) {
        const std::string path = dir + "/t" + std::to_string(i) + ".exr";
        ASSERT_EQ(mirage("render '" + scene + "' -q --threads 2 --region " + regions[i] + " -o '" +
                             path + "'",
                         &out),
                  0)
            << out;
        tiles += " '" + path + "'";
    }
    ASSERT_EQ(mirage("assemble" + tiles + " -o '" + dir + "/frame.exr'", &out), 0) << out;
    const Exr frame = readAll(dir + "/frame.exr"), full = readAll(dir + "/full.exr");
    EXPECT_EQ(frame.spec.x, 0);
    EXPECT_EQ(frame.spec.width, 40);
    EXPECT_EQ(frame.spec.height, 24);
    EXPECT_EQ(frame.spec.channelnames, full.spec.channelnames);
    EXPECT_EQ(frame.spec.format, full.spec.format);
    EXPECT_EQ(differences(frame, full), 0u);
    EXPECT_EQ(frame.spec.get_string_attribute("mirage:complete"), "true");
    EXPECT_EQ(frame.spec.get_string_attribute("mirage:region"), "");
    EXPECT_EQ(frame.spec.get_string_attribute("mirage:assembled_regions"), "4");
    EXPECT_EQ(frame.spec.get_string_attribute("mirage:fingerprint"),
              full.spec.get_string_attribute("mirage:fingerprint"));

    // A missing region: the uncovered pixels are named.
    EXPECT_EQ(mirage("assemble '" + dir + "/t0.exr' '" + dir + "/t1.exr' '" + dir +
                         "/t2.exr' -o '" + dir + "/bad.exr'",
                     &out),
              1);
    EXPECT_NE(out.find("299 pixels within 17,11,40,24 are in no region"), std::string::npos) << out;
    // An overlap: both files and the shared pixels.
    EXPECT_EQ(mirage("assemble" + tiles + " '" + dir + "/full.exr' -o '" + dir + "/bad.exr'", &out),
              1);
    EXPECT_NE(out.find("full.exr: overlaps"), std::string::npos) << out;
    EXPECT_NE(out.find("t0.exr in pixels 0,0,17,11"), std::string::npos) << out;
    // A region of another render (another seed): refused by its fingerprint.
    ASSERT_EQ(
        mirage("render '" + scene + "' -q --seed 4 --region 17,11,40,24 -o '" + dir + "/other.exr'",
               &out),
        0);
    EXPECT_EQ(mirage("assemble '" + dir + "/t0.exr' '" + dir + "/t1.exr' '" + dir + "/t2.exr' '" +
                         dir + "/other.exr' -o '" + dir + "/bad.exr'",
                     &out),
              1);
    EXPECT_NE(out.find("other.exr: not a region of the same frame"), std::string::npos) << out;
    EXPECT_NE(out.find("mirage:fingerprint"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir + "/bad.exr"));
}

// Layers other than the beauty (AOVs) carry over by channel name, at their own pixel type.
TEST(AssembleCli, EveryChannelCarriesOverByName) {
    const std::string dir = test::tempDir();
    const std::vector<std::string> names = {"A", "B", "G", "R", "depth.Z", "diffuse.R"};
    std::string tiles;
    for (int t = 0; t < 2; ++t) {
        OIIO::ImageSpec spec(3, 2, int(names.size()), OIIO::TypeHalf);
        spec.channelnames = names;
        spec.channelformats.assign(names.size(), OIIO::TypeHalf);
        spec.channelformats[4] = OIIO::TypeFloat;
        spec.x = 3 * t;
        spec.full_width = 6;
        spec.full_height = 2;
        spec.attribute("mirage:complete", "true");
        spec.attribute("mirage:fingerprint", "0123456789abcdef");
        std::vector<float> px(3 * 2 * names.size());
        for (size_t i = 0; i < px.size(); ++i) px[i] = float(t * 1000 + int(i)) + 0.25f;
        const std::string path = dir + "/t" + std::to_string(t) + ".exr";
        auto o = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(o && o->open(path, spec) && o->write_image(OIIO::TypeFloat, px.data()) &&
                    o->close());
        tiles += " '" + path + "'";
    }
    std::string out;
    ASSERT_EQ(mirage("assemble" + tiles + " -o '" + dir + "/frame.exr'", &out), 0) << out;
    const Exr frame = readAll(dir + "/frame.exr");
    EXPECT_EQ(frame.spec.width, 6);
    // OpenImageIO lists R, G, B, A first whatever the file's (sorted) order.
    const std::vector<std::string> read = {"R", "G", "B", "A", "depth.Z", "diffuse.R"};
    EXPECT_EQ(frame.spec.channelnames, read);
    EXPECT_EQ(frame.spec.channelformat(4), OIIO::TypeFloat);
    EXPECT_EQ(frame.spec.channelformat(5), OIIO::TypeHalf);
    for (int t = 0; t < 2; ++t) {
        const Exr tile = readAll(dir + "/t" + std::to_string(t) + ".exr");
        EXPECT_EQ(differences(tile, frame), 0u) << "tile " << t;
    }
}

}  // namespace mirage
