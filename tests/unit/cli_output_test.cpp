// What `mirage info FILE.vdb` and a render print for a person: every grid field a person
// needs (name, type, class, voxel size, index and world bounds, active
// voxels, memory, transform) with the active-voxel count and index bounds agreeing with
// OpenVDB's own `vdb_print`; the physics terms and why; the plain progress log when stderr is
// not a terminal; the end-of-frame summary (phases, samples, peak memory); and silence with
// --quiet.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <string>

#include "test_support.h"

namespace mirage {
namespace {

bool has(const std::string& text, const std::string& what) {
    return text.find(what) != std::string::npos;
}

TEST(CliOutput, InfoOnAVdbListsEveryGridFieldAndThePhysics) {
    const std::string vdb = test::makeFogSphere(test::tempDir());
    std::string info;
    ASSERT_EQ(test::runMirage("info '" + vdb + "'", &info), 0) << info;
    for (const char* field :
         {"'density'", "type float", "class fog volume", "compression",
          "voxel size (0.125, 0.125, 0.125) m", "index bbox", "world bounds", "active voxels",
          "memory", "transform voxel size", "grid bytes at", "voxels: not read"})
        EXPECT_TRUE(has(info, field)) << field << " missing in\n" << info;
    // Without --load, nothing that needs the voxels: no slot, maximum or physics.
    for (const char* loaded : {"slot 'density'", "physics:", "max σt"})
        EXPECT_FALSE(has(info, loaded)) << loaded << " in\n" << info;
    // --load describes the scene the file becomes, as before.
    std::string scene;
    ASSERT_EQ(test::runMirage("info --load '" + vdb + "'", &scene), 0) << scene;
    for (const char* field : {"'density'", "slot 'density'", "physics:", "[on ] absorption",
                              "[off] emission", "[off] curved paths"})
        EXPECT_TRUE(has(scene, field)) << field << " missing in\n" << scene;

    // The active-voxel count and index box agree with OpenVDB's vdb_print.
    std::string peer;
    if (test::runCommand("vdb_print -l '" + vdb + "'", &peer) != 0)
        GTEST_SKIP() << "vdb_print (libopenvdb-tools) is not installed";
    std::smatch m;
    ASSERT_TRUE(std::regex_search(peer, m, std::regex("Number of active voxels:\\s+([0-9,]+)")))
        << peer;
    std::string count = m[1];
    count.erase(std::remove(count.begin(), count.end(), ','), count.end());
    EXPECT_TRUE(has(info, "active voxels " + count)) << count << "\n" << info;
    ASSERT_TRUE(std::regex_search(peer, m,
                                  std::regex("active voxels: \\[(-?\\d+), (-?\\d+), (-?\\d+)\\] -> "
                                             "\\[(-?\\d+), (-?\\d+), (-?\\d+)\\]")))
        << peer;
    const std::string box = "index bbox [" + std::string(m[1]) + " " + std::string(m[2]) + " " +
                            std::string(m[3]) + "].." + "[" + std::string(m[4]) + " " +
                            std::string(m[5]) + " " + std::string(m[6]) + "]";
    EXPECT_TRUE(has(info, box)) << box << "\n" << info;
}

TEST(CliOutput, InfoOnASceneSaysWhichGridsHaveADenseCopy) {
    // The fog sphere's 16³ grid is far inside the dense copy's budget (volume/dense_block.h).
    const std::string dir = test::tempDir();
    test::makeFogSphere(dir);
    const std::string scene = test::writeFogSphereScene(dir, "resolution = [8, 8]\n", "");
    std::string info;
    ASSERT_EQ(test::runMirage("info '" + scene + "'", &info), 0) << info;
    EXPECT_TRUE(std::regex_search(info, std::regex("slot 'density' .* NanoVDB [0-9.]+ [KMG]?i?B at "
                                                   "precision float \\(the default for grids "
                                                   "stored as float\\), dense copy [0-9.]+ "
                                                   "[KMG]?i?B")))
        << info;
}

TEST(CliOutput, RenderLogsProgressAndSummaryAndQuietSilencesThem) {
    const std::string dir = test::tempDir();
    const std::string vdb = test::makeFogSphere(dir);
    std::string log;
    // runMirage reads stderr through a pipe: not a terminal, so the plain line log.
    ASSERT_EQ(test::runMirage("render '" + vdb + "' -o '" + dir +
                                  "/a.exr' --resolution 64x32 --spp 2 --threads 2",
                              &log),
              0)
        << log;
    EXPECT_TRUE(has(log, "render: 100% (2/2 tiles)")) << log;
    EXPECT_FALSE(has(log, "\r")) << "a terminal's bar in a log";
    for (const char* field :
         {"frame 1: 64x32, 2 spp, 4096 samples", "load ", "render ", "write ", "medium lookups/s",
          "non-finite dropped: 0 samples", "capped paths 0", "peak memory", "done: 1 frame(s)"})
        EXPECT_TRUE(has(log, field)) << field << " missing in\n" << log;

    ASSERT_EQ(
        test::runMirage(
            "render '" + vdb + "' -o '" + dir + "/b.exr' --resolution 64x32 --spp 2 --quiet", &log),
        0)
        << log;
    EXPECT_FALSE(has(log, "render:")) << log;
    EXPECT_FALSE(has(log, "frame 1:")) << log;
    EXPECT_FALSE(has(log, "peak memory")) << log;
}

// On a terminal (a pseudo-terminal from util-linux `script`), the progress is one bar redrawn
// in place: carriage returns, percentage, tiles done and an ETA.
TEST(CliOutput, RenderOnATerminalDrawsABarWithTilesAndEta) {
    if (test::runCommand("command -v script") != 0)
        GTEST_SKIP() << "util-linux `script` is absent: no pseudo-terminal to test with";
    const std::string dir = test::tempDir();
    const std::string vdb = test::makeFogSphere(dir);
    std::string out;
    ASSERT_EQ(
        test::runCommand("script -qec \"'" + test::mirageBinary() + "' render '" + vdb + "' -o '" +
                             dir + "/t.exr' --resolution 128x64 --spp 4 --threads 2\" /dev/null",
                         &out),
        0)
        << out;
    EXPECT_TRUE(has(out, "\rrender [")) << out;
    EXPECT_TRUE(has(out, "8/8 tiles")) << out;
    EXPECT_TRUE(has(out, "100.0%")) << out;
    EXPECT_TRUE(has(out, "ETA")) << out;
    EXPECT_TRUE(has(out, "frame 1: 128x64")) << out;
}

}  // namespace
}  // namespace mirage
