// Grid expressions (OpenVDB AX) on a volume's grids before NanoVDB conversion: results against
// closed forms on tiny grids written to a temporary folder, threshold and combine, inactive
// voxels left alone, the voxel rule after an expression, shader expressions over bound slots,
// errors naming the scene or shader file and line through the CLI, `mirage info`, and a render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/error.h"
#include "core/module.h"
#include "film/color.h"
#include "film/image_io.h"
#include "scene/scene.h"
#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

float nanoValue(const FloatGrid& g, int i, int j, int k) {
    return g.grid()->tree().getValue(nanovdb::Coord(i, j, k));
}

bool nanoActive(const FloatGrid& g, int i, int j, int k) {
    return g.grid()->tree().isActive(nanovdb::Coord(i, j, k));
}

GridExpression expression(const std::string& code) {
    return GridExpression{code, FileLoc{"test.toml", 7, 14}, "'expression' in [volume]", {}};
}

// density = 0.05 i at voxel (i, 0, 0), i = 0..20: the whole range of a remap.
TestGridSpec rampGrid() {
    TestGridSpec spec;
    for (int i = 0; i <= 20; ++i) spec.voxels.push_back({i, 0, 0, 0.05 * i});
    return spec;
}

// Writes `text` to dir/name and returns the path.
std::string writeText(const std::string& dir, const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
}

// 1-based line of the first line of `text` that contains `needle`.
int lineOf(const std::string& text, const std::string& needle) {
    const size_t at = text.find(needle);
    return at == std::string::npos ? 0 : 1 + int(std::count(text.begin(), text.begin() + at, '\n'));
}

// A fog-sphere scene (make-asset fog-sphere at 16³ in dir) with `volumeExtra` in its volume.
std::string sphereScene(const std::string& volumeExtra, const std::string& shader = "smoke") {
    return "[film]\nresolution = [24, 24]\nspp = 2\n"
           "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 40\n"
           "[[volume]]\nfile = \"fog.vdb\"\nshader = \"" + shader + "\"\n" +
           "density_scale = 4.0\n" + volumeExtra +
           "\n[[light]]\ntype = \"sun\"\ndirection = [0.6, -0.7, -0.4]\n"
           "irradiance = 1476.0\n";
}

// ---- Results against closed forms --------------------------------------------------------

TEST(GridExpression, RemapMatchesTheClosedFormOnEveryVoxel) {
    const std::string path = test::tempDir() + "/ramp.vdb";
    writeTestGrid(path, rampGrid());
    std::vector<double> seconds;
    std::vector<FloatGrid> grids = loadFloatGrids(
        path, {"density"}, {expression("@density = clamp((@density - 0.05) * 4.0, 0.0, 1.0);")},
        &seconds);
    ASSERT_EQ(grids.size(), 1u);
    ASSERT_EQ(seconds.size(), 1u);
    EXPECT_GT(seconds[0], 0.0);
    for (int i = 0; i <= 20; ++i) {
        const float v = float(0.05 * i);
        const float expected = std::clamp((v - 0.05f) * 4.f, 0.f, 1.f);
        EXPECT_NEAR(nanoValue(grids[0], i, 0, 0), expected, 1e-6f) << "voxel " << i;
    }
    EXPECT_EQ(grids[0].maxValue(), 1.f);
    // The expression changes values, never topology: every voxel is still active.
    EXPECT_EQ(grids[0].activeVoxels(), 21u);
}

TEST(GridExpression, ThresholdAndCombineOfTwoGrids) {
    const std::string path = test::tempDir() + "/two.vdb";
    TestGridSpec density = rampGrid(), flame;
    flame.name = "flame";
    for (int i = 10; i <= 25; ++i) flame.voxels.push_back({i, 0, 0, 0.1 * (i - 9)});
    writeTestGrids(path, {density, flame});

    // Threshold: below 0.5 becomes 0, the rest stays.
    FloatGrid thresholded = loadFloatGrids(
        path, {"density"}, {expression("if (@density < 0.5) @density = 0.0;")})[0];
    for (int i = 0; i <= 20; ++i) {
        const float v = float(0.05 * i);
        EXPECT_EQ(nanoValue(thresholded, i, 0, 0), v < 0.5f ? 0.f : v) << "voxel " << i;
    }

    // Combine: only `density` is asked for, so `flame` is read for the expression alone. Where
    // flame is inactive it reads as its background, 0.
    FloatGrid combined =
        loadFloatGrids(path, {"density"}, {expression("@density = @density * @flame;")})[0];
    EXPECT_EQ(combined.name(), "density");
    for (int i = 0; i <= 20; ++i) {
        const float d = float(0.05 * i), f = i >= 10 ? float(0.1 * (i - 9)) : 0.f;
        EXPECT_NEAR(nanoValue(combined, i, 0, 0), d * f, 1e-6f) << "voxel " << i;
    }
    // Flame voxels beyond density's active region are not written (AX writes only where the
    // target is active): density stays 0 and inactive there.
    EXPECT_EQ(nanoValue(combined, 22, 0, 0), 0.f);
    EXPECT_FALSE(nanoActive(combined, 22, 0, 0));

    // Two expressions run in order: the second sees the first's result.
    FloatGrid chained = loadFloatGrids(
        path, {"density"},
        {expression("@density = @density * 2.0;"), expression("@density = @density + 1.0;")})[0];
    EXPECT_NEAR(nanoValue(chained, 4, 0, 0), 0.2f * 2.f + 1.f, 1e-6f);
}

TEST(GridExpression, InactiveVoxelsAreUntouched) {
    const std::string path = test::tempDir() + "/inactive.vdb";
    TestGridSpec spec;
    spec.voxels = {{0, 0, 0, 0.25}, {1, 0, 0, 0.5}};
    spec.inactiveVoxels = {{2, 0, 0, 0.75}, {3, 0, 0, 0.125}};
    writeTestGrid(path, spec);

    FloatGrid before = loadFloatGrid(path, "density");
    ASSERT_FALSE(nanoActive(before, 2, 0, 0));
    ASSERT_EQ(nanoValue(before, 2, 0, 0), 0.75f);  // the file keeps the inactive value

    FloatGrid after = loadFloatGrids(path, {"density"}, {expression("@density = 9.0;")})[0];
    EXPECT_EQ(nanoValue(after, 0, 0, 0), 9.f);
    EXPECT_EQ(nanoValue(after, 1, 0, 0), 9.f);
    EXPECT_EQ(nanoValue(after, 2, 0, 0), 0.75f);
    EXPECT_EQ(nanoValue(after, 3, 0, 0), 0.125f);
    EXPECT_FALSE(nanoActive(after, 2, 0, 0));
    EXPECT_EQ(after.activeVoxels(), before.activeVoxels());
}

TEST(GridExpression, NonFiniteAndNegativeResultsFollowTheVoxelRule) {
    const std::string path = test::tempDir() + "/rule.vdb";
    writeTestGrid(path, rampGrid());
    testing::internal::CaptureStderr();
    // 0.05 i − 0.5 is negative below i = 10, √−1 is NaN at i = 10, and 10²⁰ at i = 20 is
    // above kMaxVoxelValue.
    FloatGrid g = loadFloatGrids(
        path, {"density"},
        {expression("@density = @density - 0.5; if (@density == 0.0) @density = sqrt(-1.0);"
                    " if (@density > 0.49) @density = 1e20;")})[0];
    const std::string err = testing::internal::GetCapturedStderr();
    for (int i = 0; i <= 10; ++i) EXPECT_EQ(nanoValue(g, i, 0, 0), 0.f) << "voxel " << i;
    EXPECT_NEAR(nanoValue(g, 15, 0, 0), 0.25f, 1e-6f);
    EXPECT_EQ(nanoValue(g, 20, 0, 0), kMaxVoxelValue);
    EXPECT_EQ(g.sanitizedVoxels(), 12u);
    EXPECT_NE(err.find("grid 'density' (after its expression): 11 voxels were negative or NaN"),
              std::string::npos)
        << err;
}

// ---- Scenes and shaders ------------------------------------------------------------------

TEST(GridExpression, ShaderExpressionSpeaksOfSlotsThroughTheVolumesBind) {
    const std::string dir = test::tempDir();
    TestGridSpec smoke = rampGrid(), mask;
    smoke.name = "smoke";
    mask.name = "mask";
    mask.voxels = {{20, 0, 0, 0.5}};
    writeTestGrids(dir + "/cache.vdb", {smoke, mask});
    writeText(dir, "doubled.toml",
              "name = \"doubled\"\nexpression = \"@density = 2.0 * @density;\"\n"
              "[[component]]\ngrid = \"density\"\nsigma_a = 1.0\n");
    const std::string scene = writeText(
        dir, "scene.toml",
        "[[volume]]\nfile = \"cache.vdb\"\nshader = \"doubled\"\n"
        "bind = { density = \"smoke\" }\nexpression = \"@smoke = @smoke * @mask;\"\n");
    ColorPipeline color;
    Scene s = loadScene(scene, LoadOptions{}, color);
    // Shader first (×2), then the volume's (× mask): 2 · 1.0 · 0.5 at voxel 20, 0 elsewhere.
    const FloatGrid& g = s.render.media[0]->binding().grids()[0];
    EXPECT_NEAR(nanoValue(g, 20, 0, 0), 1.f, 1e-6f);
    EXPECT_EQ(nanoValue(g, 10, 0, 0), 0.f);
    ASSERT_EQ(s.volumes[0].expressions.size(), 2u);
    EXPECT_EQ(s.volumes[0].expressions[0].origin, "shader 'doubled'");
    EXPECT_EQ(describeAccess(s.volumes[0].expressions[0].access),
              "reads 'smoke'; writes 'smoke'");
    EXPECT_EQ(describeAccess(s.volumes[0].expressions[1].access),
              "reads 'mask', 'smoke'; writes 'smoke'");
    // The mask is read by the expression, so it is not reported as unused.
    EXPECT_TRUE(s.volumes[0].unusedGrids.empty());
}

TEST(GridExpression, InfoSaysWhichGridsAnExpressionReadsAndWrites) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fire", dir + "/fire.vdb", 16, 1);
    const std::string scene = writeText(
        dir, "fire.toml",
        "[[volume]]\nfile = \"fire.vdb\"\nexpression = \"@density = @density * @flame;\"\n");
    std::string out;
    ASSERT_EQ(test::runMirage("info '" + scene + "'", &out), 0) << out;
    EXPECT_NE(out.find("expression (volume, " + scene + ":3:14): reads 'flame', 'density'; "
                       "writes 'density'"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("[on ] grid expressions"), std::string::npos) << out;
    // flame is loaded for the expression; temperature is read by nothing.
    EXPECT_EQ(out.find("grid 'flame' is read by no"), std::string::npos) << out;
    EXPECT_NE(out.find("grid 'temperature' is read by no shader slot or expression"),
              std::string::npos)
        << out;

    std::string plain;
    const std::string noExpr =
        writeText(dir, "plain.toml", "[[volume]]\nfile = \"fire.vdb\"\n");
    ASSERT_EQ(test::runMirage("info '" + noExpr + "'", &plain), 0) << plain;
    EXPECT_NE(plain.find("[off] grid expressions"), std::string::npos) << plain;
}

// ---- Errors ------------------------------------------------------------------------------

TEST(GridExpression, BadExpressionsGiveOneMessageWithFileAndLineAndExitNonZero) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    struct Case {
        std::string expr, needle;
    } cases[] = {
        {"@density = @density *;", "OpenVDB AX syntax error: unexpected SEMICOLON 1:22"},
        {"@density = frobnicate(@density);", "unable to locate function \"frobnicate\""},
        {"@density = @density * @flame;",
         "the expression names grid 'flame', but " + dir + "/fog.vdb has no such grid"},
        {"v@density = 1;", "grid 'density' is accessed as vec3f"},
    };
    for (const Case& c : cases) {
        const std::string text = sphereScene("expression = \"" + c.expr + "\"");
        const std::string scene = writeText(dir, "bad.toml", text);
        const std::string where =
            scene + ":" + std::to_string(lineOf(text, "expression")) + ":14: ";
        std::string out;
        EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + dir + "/bad.exr' --quiet", &out),
                  1)
            << out;
        EXPECT_NE(out.find("mirage: error: " + where + "'expression' in [volume]: "),
                  std::string::npos)
            << c.expr << "\n" << out;
        EXPECT_NE(out.find(c.needle), std::string::npos) << c.expr << "\n" << out;
        EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;  // one line
        EXPECT_FALSE(std::ifstream(dir + "/bad.exr").good());
    }

    // In a shader file, the shader file and its line are named.
    const std::string shaderText =
        "name = \"broken\"\n[[component]]\ngrid = \"density\"\nsigma_s = 1.0\n";
    writeText(dir, "broken.toml", "expression = \"@density = (;\"\n" + shaderText);
    const std::string scene = writeText(dir, "uses_broken.toml", sphereScene("", "broken"));
    std::string out;
    EXPECT_EQ(test::runMirage("info '" + scene + "'", &out), 1) << out;
    EXPECT_NE(out.find(dir + "/broken.toml:1:14: 'expression' of shader 'broken': OpenVDB AX "
                             "syntax error"),
              std::string::npos)
        << out;
}

// ---- A render ----------------------------------------------------------------------------

TEST(GridExpression, ThresholdChangesTheRender) {
    const std::string dir = test::tempDir();
    writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    auto render = [&](const std::string& name, const std::string& extra) {
        const std::string scene = writeText(dir, name + ".toml", sphereScene(extra));
        std::string out;
        EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + dir + "/" + name +
                                      ".exr' --quiet --threads 2",
                                  &out),
                  0)
            << out;
        return readExr(dir + "/" + name + ".exr");
    };
    auto sums = [](const Image& im) {
        double rgb = 0, alpha = 0;
        for (size_t i = 0; i < im.rgba.size(); i += 4) {
            rgb += im.rgba[i] + im.rgba[i + 1] + im.rgba[i + 2];
            alpha += im.rgba[i + 3];
        }
        return std::make_pair(rgb, alpha);
    };
    const auto plain = sums(render("plain", ""));
    // The sphere's density is at most 1: this threshold removes all of it.
    const auto gone = sums(render("gone", "expression = \"if (@density < 2.0) @density = 0.0;\""));
    // Keeping only the core (density 1 within 0.6 m) leaves a smaller, fainter sphere.
    const auto core = sums(render("core", "expression = \"if (@density < 0.99) @density = 0.0;\""));
    EXPECT_GT(plain.first, 0.0);
    EXPECT_GT(plain.second, 24.0 * 24.0 * 0.1);
    EXPECT_EQ(gone.first, 0.0);
    EXPECT_EQ(gone.second, 0.0);
    EXPECT_GT(core.second, 0.0);
    EXPECT_LT(core.second, plain.second);
}

// AX comes from Mirage's module, loaded when a scene first has an expression (volume/ax_module.h):
// the command does not link libopenvdb_ax (LLVM's relocations at every start), and a module
// that cannot be found is one message naming it, what needed it and where it was looked for.
TEST(GridExpression, AxIsAModuleLoadedOnDemand) {
    std::string dynamic;
    ASSERT_EQ(test::runCommand("readelf -d " + test::mirageBinary(), &dynamic), 0);
    EXPECT_NE(dynamic.find("libtbb"), std::string::npos) << dynamic;
    EXPECT_EQ(dynamic.find("openvdb_ax"), std::string::npos) << dynamic;
    try {
        moduleEntry("libmirage_absent.so", "entry", "testing modules");
        FAIL() << "expected a MirageError";
    } catch (const MirageError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("testing modules need Mirage's module libmirage_absent.so"),
                  std::string::npos) << m;
        EXPECT_NE(m.find("/libmirage_absent.so"), std::string::npos) << m;
    }
}

}  // namespace
}  // namespace mirage
