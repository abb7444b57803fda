// The precision a volume's grids load at when the scene does not say (scene/precision_loader.h,
// choosePrecision): half (NanoVDB Fp16) for grids stored as half floats and too big for a float
// dense copy; float for grids stored as float, for grids small enough for a dense copy, where an
// expression writes a grid, and whenever the scene states a precision. `mirage info` says which
// and why.
#include <gtest/gtest.h>

#include <fstream>

#include "film/color.h"
#include "scene/scene.h"
#include "test_grids.h"
#include "test_support.h"

namespace mirage {
namespace {

// A grid of two voxels `apart` voxels apart on each axis, stored as half floats or not: 800
// apart, its float dense copy would need 2 GB (over the budget, volume/dense_block.h); 8 apart,
// a few kB.
std::string writeGrid(const std::string& dir, int apart, bool half) {
    TestGridSpec spec;
    spec.saveAsHalf = half;
    spec.voxels = {{0, 0, 0, 0.5}, {apart, apart, apart, 0.25}};
    const std::string path =
        dir + "/grid_" + std::to_string(apart) + (half ? "_half" : "") + ".vdb";
    writeTestGrid(path, spec);
    return path;
}

std::string writeScene(const std::string& dir, const std::string& vdb, const std::string& keys) {
    std::ofstream(dir + "/scene.toml")
        << "[film]\nresolution = [8, 8]\n[camera]\nposition = [0, 1, 40]\nlook_at = [0, 1, 0]\n"
           "[[volume]]\nfile = \""
        << vdb << "\"\n"
        << keys << "\n[[light]]\ntype = \"sun\"\ndirection = [0, -1, 0]\nirradiance = 1\n";
    return dir + "/scene.toml";
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// The scene's grid loads at `precision`, for the reason that contains `why`.
void expectLoads(const std::string& scene, GridPrecision precision, const std::string& why) {
    static ColorPipeline color;
    const Scene s = loadScene(scene, LoadOptions{}, color);
    EXPECT_EQ(s.render.media[0]->binding().grids()[0].precision(), precision);
    EXPECT_TRUE(has(s.volumes[0].precisionWhy, why)) << s.volumes[0].precisionWhy;
}

TEST(DefaultPrecision, HalfStoredGridsTooBigForADenseCopyLoadAsFp16) {
    const std::string dir = test::tempDir();
    const std::string wideHalf = writeGrid(dir, 800, true);
    expectLoads(writeScene(dir, wideHalf, ""), GridPrecision::Half,
                "stored as half floats and too big for a dense copy");
    expectLoads(writeScene(dir, writeGrid(dir, 8, true), ""), GridPrecision::Float,
                "small enough for a dense copy");
    expectLoads(writeScene(dir, writeGrid(dir, 800, false), ""), GridPrecision::Float,
                "stored as float");
    expectLoads(writeScene(dir, wideHalf, "precision = \"float\""), GridPrecision::Float,
                "as the scene states");
    expectLoads(writeScene(dir, wideHalf, "expression = \"@density = @density * 2;\""),
                GridPrecision::Float, "an expression writes a grid");
}

TEST(DefaultPrecision, InfoSaysThePrecisionAndWhy) {
    const std::string dir = test::tempDir();
    std::string out;
    ASSERT_EQ(
        test::runMirage("info '" + writeScene(dir, writeGrid(dir, 800, true), "") + "'", &out), 0)
        << out;
    EXPECT_TRUE(has(out, "at precision half (the default for grids stored as half floats")) << out;
    ASSERT_EQ(
        test::runMirage(
            "info '" + writeScene(dir, writeGrid(dir, 800, true), "precision = \"fp8\"") + "'",
            &out),
        0)
        << out;
    EXPECT_TRUE(has(out, "at precision fp8 (as the scene states)")) << out;
}

}  // namespace
}  // namespace mirage
