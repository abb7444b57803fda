// Bare pyro caches (`mirage render FILE.vdb`, scene/pyro_binding.h): which grids bind to what,
// and the frame ranges of a sequence (--frames A-BxS).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "film/color.h"
#include "puff_scene.h"
#include "render/integrator.h"
#include "render/renderer.h"
#include "scene/pyro_binding.h"
#include "scene/scene.h"
#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"

namespace mirage {
namespace {

std::string boundTo(const VolumeRecord& v, const std::string& slot) {
    for (const auto& [s, g] : v.bindings)
        if (s == slot) return g;
    return "";
}

bool listed(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

// A ball of `value` in each named grid (and a ball of density 1).
std::string writeCache(const std::string& dir,
                       const std::vector<std::pair<std::string, double>>& grids) {
    std::vector<TestGridSpec> specs;
    for (const auto& [name, value] : grids) {
        TestGridSpec g;
        g.name = name;
        for (int i = -3; i <= 3; ++i)
            for (int j = -3; j <= 3; ++j)
                for (int k = -3; k <= 3; ++k)
                    if (i * i + j * j + k * k <= 9) g.voxels.push_back({i, j, k, value});
        specs.push_back(g);
    }
    const std::string path = dir + "/cache.vdb";
    writeTestGrids(path, specs);
    return path;
}

TEST(PyroCache, MakeAssetFireBindsTheFireShaderInKelvinAndBlurs) {
    const std::string dir = test::tempDir();
    const std::string path = dir + "/fire.vdb";
    writeProceduralAsset("fire", path, 32, 1);
    ColorPipeline color;
    LoadOptions o{1, {"film.resolution=[32, 24]", "film.spp=2"}};
    o.shutter = ShutterFrames{-0.25, 0.25};
    Scene scene = loadScene(path, o, color);
    const VolumeRecord& v = scene.volumes.at(0);
    EXPECT_EQ(v.shader, "fire");
    EXPECT_EQ(boundTo(v, "density"), "density");
    EXPECT_EQ(boundTo(v, "temperature"), "temperature");
    EXPECT_EQ(boundTo(v, "flame"), "flame");
    const Medium& m = *scene.render.media.at(0);
    ASSERT_TRUE(m.emissive());
    EXPECT_EQ(m.shader().emission->temperatureScale, 1.f);  // make-asset writes kelvin
    EXPECT_EQ(m.shader().emission->temperatureOffset, 0.f);
    EXPECT_EQ(v.velocity.grid, "vel");
    EXPECT_TRUE(m.motion().moving());
    EXPECT_FALSE(v.notes.empty());
    const RenderStats stats = puff::renderStats(scene, "single");
    EXPECT_EQ(stats.aboveMajorant, 0u);
    EXPECT_EQ(stats.nonFiniteSamples, 0u);
}

TEST(PyroCache, MakeAssetSmokeStaysSmoke) {
    const std::string dir = test::tempDir();
    const std::string path = dir + "/smoke.vdb";
    writeProceduralAsset("smoke", path, 24, 1);
    ColorPipeline color;
    Scene scene = loadScene(path, LoadOptions{}, color);
    EXPECT_EQ(scene.volumes.at(0).shader, "smoke");
    EXPECT_FALSE(scene.render.media.at(0)->emissive());
}

TEST(PyroCache, RelativeHeatGlowsInKelvinWithoutAFlameComponent) {
    const std::string dir = test::tempDir();
    const std::string path = writeCache(dir, {{"density", 1.0}, {"heat", 1.5}});
    ColorPipeline color;
    Scene scene = loadScene(path, LoadOptions{}, color);
    const VolumeRecord& v = scene.volumes.at(0);
    EXPECT_EQ(v.shader, "fire");
    EXPECT_EQ(boundTo(v, "temperature"), "heat");
    const Medium& m = *scene.render.media.at(0);
    ASSERT_TRUE(m.emissive());
    EXPECT_EQ(m.shader().components.size(), 1u);  // soot only: no flame grid
    // 1.5 relative → 300 K + 1000 K × 1.5 = 1800 K.
    const EmissionSpec& e = *m.shader().emission;
    EXPECT_FLOAT_EQ(e.temperatureScale * 1.5f + e.temperatureOffset, 1800.f);
}

TEST(PyroCache, FlameAloneSetsTheTemperature) {
    const std::string dir = test::tempDir();
    const std::string path = writeCache(dir, {{"density", 1.0}, {"flame", 1.0}});
    ColorPipeline color;
    Scene scene = loadScene(path, LoadOptions{}, color);
    const VolumeRecord& v = scene.volumes.at(0);
    EXPECT_EQ(v.shader, "fire");
    EXPECT_EQ(boundTo(v, "temperature"), "flame");
    EXPECT_EQ(boundTo(v, "flame"), "flame");
    const EmissionSpec& e = *scene.render.media.at(0)->shader().emission;
    EXPECT_FLOAT_EQ(e.temperatureScale + e.temperatureOffset, 1800.f);  // full reaction
}

TEST(PyroCache, RelativeTemperatureWithoutFlameIsSmokeBuoyancy) {
    const std::string dir = test::tempDir();
    const std::string path =
        writeCache(dir, {{"density", 1.0}, {"temperature", 0.8}, {"other", 1.0}});
    ColorPipeline color;
    Scene scene = loadScene(path, LoadOptions{}, color);
    const VolumeRecord& v = scene.volumes.at(0);
    EXPECT_EQ(v.shader, "smoke");
    EXPECT_TRUE(listed(v.unusedGrids, "temperature"));
    EXPECT_TRUE(listed(v.unusedGrids, "other"));
    ASSERT_EQ(v.notes.size(), 1u);
    EXPECT_NE(v.notes[0].find("warm air"), std::string::npos) << v.notes[0];
}

TEST(PyroCache, SharedCachesBindAsTheirSimulatorsMeantThem) {
    MIRAGE_REQUIRE_SHARED(mantaflow, "vdb/mantaflow_smoke.0009.vdb");
    MIRAGE_REQUIRE_SHARED(heat, "vdb/density_and_heat.vdb");
    ColorPipeline color;
    LoadOptions o;
    o.shutter = ShutterFrames{-0.25, 0.25};
    Scene smoke = loadScene(mantaflow, o, color);
    EXPECT_EQ(smoke.volumes.at(0).shader, "smoke");
    EXPECT_TRUE(listed(smoke.volumes.at(0).unusedGrids, "temperature"));
    EXPECT_EQ(smoke.volumes.at(0).velocity.grid, "velocity");
    EXPECT_TRUE(smoke.volumes.at(0).velocity.velocity.staggered());
    EXPECT_NE(describeVelocity(smoke.volumes.at(0).velocity).find("staggered"), std::string::npos);
    Scene fire = loadScene(heat, LoadOptions{}, color);
    EXPECT_EQ(fire.volumes.at(0).shader, "fire");
    EXPECT_EQ(boundTo(fire.volumes.at(0), "temperature"), "heat");
    EXPECT_TRUE(fire.render.media.at(0)->emissive());
}

TEST(FrameRange, RangesAndSteps) {
    EXPECT_EQ(parseFrameRange("8-10"), (std::vector<int>{8, 9, 10}));
    EXPECT_EQ(parseFrameRange("1-9x4"), (std::vector<int>{1, 5, 9}));
    EXPECT_EQ(parseFrameRange("1-48x2").size(), 24u);
    EXPECT_EQ(parseFrameRange("1-48x2").back(), 47);
    for (const char* bad : {"10-8", "1-4x0", "1-4x", "1-4y2", "1-4x2z", "a-b", "3"})
        EXPECT_THROW(parseFrameRange(bad), MirageError) << bad;
}

}  // namespace
}  // namespace mirage
