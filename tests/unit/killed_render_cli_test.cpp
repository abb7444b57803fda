// Killed renders end to end, through the mirage binary: a render stopped after a few tiles (the
// test hook MIRAGE_TEST_STOP_AFTER_TILES raises the same flag SIGINT does) exits 130, leaves
// <out>.partial and no final EXR; --resume then writes the same pixels as an uninterrupted
// render; a partial file from other settings is refused; a real SIGTERM exits 143; sequences
// skip complete frames; and --max-memory refuses an impossible photon count within 2 s.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

// The procedural fog sphere, 40×24 pixels in 8-pixel tiles (15 tiles), photon integrator: the
// photon pass is re-run on resume and must give the same photons.
std::string writeScene(const std::string& dir, const std::string& integrator = "photon") {
    test::makeFogSphere(dir);
    std::ofstream f(dir + "/scene.toml");
    f << "[film]\nresolution = [40, 24]\ntile_size = 8\nspp = 2\nseed = 7\n"
         "[render]\nintegrator = \""
      << integrator
      << "\"\nphotons = 20000\n"
         "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 35\n"
         "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3\n"
         "[[light]]\ntype = \"sun\"\ndirection = [0.6, -0.7, -0.4]\nirradiance = 1476\n";
    return dir + "/scene.toml";
}

// The scene file `path` with `line` inserted after its first `section` header and `tail`
// appended, written as `out`; returns `out`.
std::string editedScene(const std::string& path, const std::string& section,
                        const std::string& line, const std::string& tail, const std::string& out) {
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.insert(text.find(section) + section.size(), line);
    std::ofstream(out) << text << tail;
    return out;
}

int render(const std::string& args, std::string* out, const std::string& env = "") {
    return test::runCommand(env + " '" + test::mirageBinary() + "' render " + args, out);
}

// Stops a render of `first` (the scene and its options) after two tiles, then resumes it as
// `second`, which must be refused; returns the refusal's output.
std::string refusedResume(const std::string& first, const std::string& second,
                          const std::string& target) {
    std::string out;
    EXPECT_EQ(render(first + " -q -o '" + target + "'", &out, "MIRAGE_TEST_STOP_AFTER_TILES=2"),
              130)
        << out;
    EXPECT_EQ(render(second + " -q --resume -o '" + target + "'", &out), 1) << out;
    EXPECT_NE(out.find("--resume refused"), std::string::npos) << out;
    return out;
}

}  // namespace

TEST(KilledRenderCli, InterruptedThenResumedEqualsUninterruptedBitForBit) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    ASSERT_EQ(render("'" + scene + "' -q --float -o '" + dir + "/ref.exr'", &out), 0) << out;

    const std::string target = dir + "/frame.exr";
    int rc = render("'" + scene + "' -q --float --threads 2 -o '" + target + "'", &out,
                    "MIRAGE_TEST_STOP_AFTER_TILES=4");
    EXPECT_EQ(rc, 130) << out;
    EXPECT_NE(out.find("--resume"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(target)) << "an interrupted frame must not leave a final EXR";
    ASSERT_TRUE(fs::exists(target + ".partial")) << out;

    // Resumed on one thread: neither the photon pass nor the tiles depend on the thread count.
    ASSERT_EQ(render("'" + scene + "' -q --float --resume --threads 1 -o '" + target + "'", &out),
              0)
        << out;
    EXPECT_FALSE(fs::exists(target + ".partial")) << "the partial file is removed once final";
    std::map<std::string, std::string> meta;
    Image a = readExr(dir + "/ref.exr"), b = readExr(target, &meta);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    size_t differ = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) differ += a.rgba[i] != b.rgba[i];
    EXPECT_EQ(differ, 0u) << "resumed pixels differ from the uninterrupted render";
    EXPECT_EQ(meta["mirage:complete"], "true");
    EXPECT_GE(std::stoi(meta["mirage:resumed_tiles"]), 4);
}

TEST(KilledRenderCli, ResumeRefusesAPartialFileFromOtherSettings) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir, "single");
    const std::string target = dir + "/frame.exr";
    std::string out;
    int rc =
        render("'" + scene + "' -q -o '" + target + "'", &out, "MIRAGE_TEST_STOP_AFTER_TILES=2");
    ASSERT_EQ(rc, 130) << out;
    rc = render("'" + scene + "' -q --resume --spp 3 -o '" + target + "'", &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("--resume refused"), std::string::npos) << out;
    EXPECT_NE(out.find("spp was '2', now '3'"), std::string::npos) << out;
    EXPECT_TRUE(fs::exists(target + ".partial")) << "a refused resume keeps the partial file";

    // The scene text itself is part of the fingerprint.
    std::ofstream(scene, std::ios::app) << "# edited\n";
    rc = render("'" + scene + "' -q --resume -o '" + target + "'", &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("scene file or one of its grid files changed"), std::string::npos) << out;
}

// A Cryptomatte's IDs are hashes of the objects' names: a volume renamed between runs would
// resume its samples under another ID, so the names are in the fingerprint, and so is the
// list of passes; a refusal names what changed.
TEST(KilledRenderCli, ResumeRefusesAPartialFileWithOtherCryptomatteNames) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir, "single");
    auto named = [&](const std::string& name) {
        return editedScene(scene, "[[volume]]\n", "name = \"" + name + "\"\n",
                           "[output]\ncryptomatte = [\"volume\"]\n", dir + "/" + name + ".toml");
    };
    const std::string target = dir + "/frame.exr";
    std::string out = refusedResume("'" + named("fog") + "'", "'" + named("mist") + "'", target);
    EXPECT_NE(out.find("crypto_volumes was 'fog', now 'mist'"), std::string::npos) << out;
    EXPECT_TRUE(fs::exists(target + ".partial")) << "a refused resume keeps the partial file";

    // Another pass beside the Cryptomatte.
    EXPECT_EQ(render("'" + named("fog") + "' -q --resume --aov depth -o '" + target + "'", &out), 1)
        << out;
    EXPECT_NE(out.find("aovs was 'crypto_volume', now 'crypto_volume, depth'"), std::string::npos)
        << out;
}

// Motion blur: the camera's keys and a turntable's rate move the camera within the shutter, so
// they are in the fingerprint; a refusal names them.
TEST(KilledRenderCli, ResumeRefusesAPartialFileWithOtherCameraMotion) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir, "single");
    auto keyed = [&](const std::string& keyX) {
        return editedScene(scene, "[camera]\n", "shutter = [-0.25, 0.25]\n",
                           "[[camera.key]]\nframe = 0\nposition = [0, 1, 4]\n"
                           "[[camera.key]]\nframe = 1\nposition = [" +
                               keyX + ", 1, 4]\n",
                           dir + "/keyed" + keyX + ".toml");
    };
    std::string out =
        refusedResume("'" + keyed("0.5") + "'", "'" + keyed("0.7") + "'", dir + "/frame.exr");
    EXPECT_NE(out.find("camera_keys was"), std::string::npos) << out;

    // A turntable's rate: the same first frame (numbered .0001), turning at another speed within
    // the shutter.
    const std::string turn = dir + "/turn.exr";
    out = refusedResume("'" + scene + "' --turntable 24 --shutter 0.5",
                        "'" + scene + "' --turntable 48 --shutter 0.5", turn);
    EXPECT_NE(out.find("turntable was"), std::string::npos) << out;
    // And the shutter given on the command line.
    int rc =
        render("'" + scene + "' -q --resume --turntable 24 --shutter 0.25 -o '" + turn + "'", &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("shutter_seconds was"), std::string::npos) << out;
}

TEST(KilledRenderCli, SigtermStopsTheRenderWithExit143AndNoFinalFile) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir, "volpath");
    const std::string target = dir + "/frame.exr";
    // The signal must arrive while tiles are still being rendered, on any machine: a fixed sleep
    // raced a fast CI machine (the whole frame finished first). So the frame is long (65536 spp,
    // about a minute on 2 cores; a 4-pixel tile takes ~1 s on one thread), and the signal is sent
    // as soon as the first finished tile shows up in <out>.partial (written after every tile with
    // MIRAGE_PARTIAL_INTERVAL=0). The wait is bounded at 120 s so that a broken partial writer
    // fails the test instead of hanging it; tiles in flight finish before the exit.
    std::string out;
    int rc =
        test::runCommand("MIRAGE_PARTIAL_INTERVAL=0 '" + test::mirageBinary() + "' render '" +
                             scene + "' -q --spp 65536 --set film.tile_size=4 --threads 2 -o '" +
                             target + "' & pid=$!; i=0; while [ ! -e '" + target +
                             ".partial' ] && [ $i -lt 1200 ]; do sleep 0.1; i=$((i+1)); done; "
                             "kill -TERM $pid; wait $pid",
                         &out);
    EXPECT_EQ(rc, 143) << out;
    EXPECT_FALSE(fs::exists(target)) << "a killed frame must not leave a final EXR";
    EXPECT_TRUE(fs::exists(target + ".partial")) << "the finished tiles are kept for --resume";
}

// A farm re-render of a frame that is already good, killed half-way, must leave the good frame
// exactly as it was: the interrupted render writes only <out>.partial.
TEST(KilledRenderCli, AKilledReRenderLeavesTheGoodFrameUntouched) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir, "single");
    const std::string target = dir + "/frame.exr";
    std::string out;
    ASSERT_EQ(render("'" + scene + "' -q -o '" + target + "'", &out), 0) << out;
    std::ifstream before(target, std::ios::binary);
    const std::string good((std::istreambuf_iterator<char>(before)),
                           std::istreambuf_iterator<char>());
    ASSERT_FALSE(good.empty());
    const int rc = render("'" + scene + "' -q --seed 9 -o '" + target + "'", &out,
                          "MIRAGE_TEST_STOP_AFTER_TILES=1");
    ASSERT_EQ(rc, 130) << out;
    std::ifstream after(target, std::ios::binary);
    const std::string now((std::istreambuf_iterator<char>(after)),
                          std::istreambuf_iterator<char>());
    EXPECT_TRUE(now == good) << "the good frame was overwritten by a killed render";
    EXPECT_TRUE(fs::exists(target + ".partial"));
}

TEST(KilledRenderCli, SkipExistingSkipsCompleteFramesOnly) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir, "single");
    const std::string pattern = dir + "/seq.####.exr";
    std::string out;
    ASSERT_EQ(render("'" + scene + "' -q --frames 1-2 -o '" + pattern + "'", &out), 0) << out;
    auto t1 = fs::last_write_time(dir + "/seq.0001.exr");
    // Frame 3 is killed: it leaves only a partial file, which is not a complete frame.
    int rc = render("'" + scene + "' -q --frame 3 -o '" + pattern + "'", &out,
                    "MIRAGE_TEST_STOP_AFTER_TILES=1");
    ASSERT_EQ(rc, 130) << out;
    ASSERT_FALSE(fs::exists(dir + "/seq.0003.exr"));

    ASSERT_EQ(render("'" + scene + "' --skip-existing --frames 1-3 -o '" + pattern + "'", &out), 0)
        << out;
    EXPECT_NE(out.find("seq.0001.exr is complete, skipped"), std::string::npos) << out;
    EXPECT_NE(out.find("seq.0002.exr is complete, skipped"), std::string::npos) << out;
    EXPECT_EQ(fs::last_write_time(dir + "/seq.0001.exr"), t1) << "a complete frame was rewritten";
    EXPECT_TRUE(fs::exists(dir + "/seq.0003.exr"));
    std::map<std::string, std::string> meta;
    readExr(dir + "/seq.0003.exr", &meta);
    EXPECT_EQ(meta["mirage:complete"], "true");
}

// A billion photons would take hours to trace (and ctest's timeout would end the test), so a
// refusal that names the photon maps is one made before the photon pass, not after it: no clock
// is needed to tell, and none is read (a wall-clock bound fails on a loaded machine).
TEST(KilledRenderCli, MaxMemoryRefusesABillionPhotonsBeforeTracingThem) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    std::string out;
    int rc = render(
        "'" + scene + "' -q --set render.photons=1000000000 --max-memory 1G -o '" + dir + "/m.exr'",
        &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("more than --max-memory 1.00 GiB"), std::string::npos) << out;
    EXPECT_NE(out.find("photon maps"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir + "/m.exr"));

    // A budget smaller than what is resident is refused before the grid is read, naming it.
    rc = render("'" + scene + "' -q --max-memory 1k -o '" + dir + "/m.exr'", &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("loading grid 'density' would need an estimated"), std::string::npos) << out;
    EXPECT_NE(out.find("fog.vdb at precision float (file metadata)"), std::string::npos) << out;

    // The same scene within budget renders; a malformed size is one clear error.
    EXPECT_EQ(render("'" + scene + "' -q --max-memory 4G -o '" + dir + "/m.exr'", &out), 0) << out;
    rc = render("'" + scene + "' -q --max-memory 12X -o '" + dir + "/m.exr'", &out);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("--max-memory '12X'"), std::string::npos) << out;
}
}  // namespace mirage
