// Grids a scene does not use are never read (docs/design.md, "Model only what a scene requires"),
// counted by the reader itself (gridReadCount): a velocity grid with the shutter closed, not even
// for `mirage info`'s description, and a grid no shader slot binds; and --max-memory refuses a
// grid that will not fit at its precision before reading it.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "film/color.h"
#include "frame/frame_load.h"
#include "scene/memory_budget.h"
#include "scene/scene_info.h"
#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "volume/grid_cache.h"
#include "volume/grid_quantise.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

// density (a 12³ block), vel (a uniform wind) and temperature, which the smoke shader reads not.
std::string writeCache(const std::string& dir) {
    TestGridSpec density, vel, temperature;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j)
            for (int k = 0; k < 12; ++k) {
                density.voxels.push_back({i, j, k, 0.5 + 0.04 * ((i + 2 * j + 3 * k) % 13)});
                vel.voxels.push_back({i, j, k, 0.0, Vec3d(1.0, 0.0, 0.0)});
                temperature.voxels.push_back({i, j, k, 900.0});
            }
    vel.name = "vel";
    vel.valueType = "vec3s";
    vel.gridClass = "unknown";
    temperature.name = "temperature";
    writeTestGrids(dir + "/cache.vdb", {density, vel, temperature});
    return dir + "/cache.vdb";
}

std::string writeScene(const std::string& dir, const std::string& camera,
                       const std::string& volume = "") {
    writeCache(dir);
    std::ofstream(dir + "/scene.toml")
        << "[film]\nresolution = [8, 8]\n[camera]\nposition = [0.6, 0.6, 4]\n"
           "look_at = [0.6, 0.6, 0.6]\n"
        << camera << "\n[[volume]]\nfile = \"cache.vdb\"\n"
        << volume << "\n[[light]]\ntype = \"sun\"\ndirection = [0, -1, 0]\nirradiance = 1\n";
    return dir + "/scene.toml";
}

TEST(UnreadGrids, InfoWithTheShutterClosedReadsNoVelocity) {
    ColorPipeline color;
    const std::string scene = writeScene(test::tempDir(), "");
    const uint64_t before = gridReadCount();
    const Scene s = loadScene(scene, LoadOptions{}, color);
    const SceneInfo info = describeScene(s, color);
    EXPECT_EQ(gridReadCount() - before, 1u) << "density only";
    EXPECT_NE(info.volumes[0].velocity.find("not loaded: the shutter is closed"), std::string::npos)
        << info.volumes[0].velocity;
    const auto& unused = info.volumes[0].unusedGrids;
    EXPECT_NE(std::find(unused.begin(), unused.end(), "temperature"), unused.end());
}

TEST(UnreadGrids, AnOpenShutterReadsTheVelocity) {
    ColorPipeline color;
    const std::string scene = writeScene(test::tempDir(), "shutter = [-0.25, 0.25]");
    const uint64_t before = gridReadCount();
    const Scene s = loadScene(scene, LoadOptions{}, color);
    describeScene(s, color);
    EXPECT_EQ(gridReadCount() - before, 2u) << "density and vel";
}

TEST(UnreadGrids, MaxMemoryRefusesAGridAtItsPrecisionBeforeReadingIt) {
    ColorPipeline color;
    GridCache cache;
    FrameRequest request;
    request.input = writeScene(test::tempDir(), "", "precision = \"fp8\"");
    request.memoryBudget = 1024;
    const uint64_t before = gridReadCount();
    std::string message;
    try {
        loadFrame(request, color, &cache);
    } catch (const MirageError& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("loading grid 'density' would need an estimated"), std::string::npos)
        << message;
    EXPECT_NE(message.find("at precision fp8 (file metadata)"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(gridReadCount(), before);
    EXPECT_EQ(cache.reads(), 0u);
}

// The estimate before reading shrinks with the precision and bounds what the grid then takes.
// `mirage info FILE.vdb` describes a bare file from its metadata and topology: no grid is read,
// yet each scalar grid's leaves and tree bytes at every precision are those of the loaded grid.
TEST(UnreadGrids, InfoOnABareFileReadsNoGridYetGivesEachGridsLeavesAndBytes) {
    const std::string dir = test::tempDir();
    const std::string path = writeCache(dir);
    const uint64_t before = gridReadCount();
    const VolumeFileInfo info = describeVolumeFile(path, 1);
    EXPECT_EQ(gridReadCount(), before);
    ASSERT_EQ(info.vdb.grids.size(), 3u);
    ASSERT_EQ(info.grids.size(), 2u) << "density and temperature; vel is a vector grid";
    // A pyro cache's trees have several root children and tiles.
    const std::string pyro = dir + "/pyro.vdb";
    writeProceduralAsset("pyro", pyro, 48, 5);
    for (const std::string& file : {path, pyro})
        for (const SlotInfo& g : describeVolumeFile(file, 1).grids) {
            SCOPED_TRACE(file + " " + g.grid);
            const FloatGrid loaded = loadFloatGrid(file, g.grid);
            EXPECT_EQ(g.leaves, loaded.leafCount());
            EXPECT_EQ(g.treeBytes, loaded.treeBytes());
            for (GridPrecision p : kAllPrecisions)
                EXPECT_EQ(g.bytesAt[size_t(p)], loaded.treeBytesAt(p)) << precisionName(p);
        }
}

TEST(UnreadGrids, EstimateBeforeReadingBoundsEachPrecision) {
    const std::string path = writeCache(test::tempDir());
    const GridInfo info = inspectVdbFile(path).grids[0];
    const FloatGrid f = loadFloatGrid(path, "density");
    uint64_t previous = gridBytesBeforeLoad(info, GridPrecision::Float);
    EXPECT_GE(previous, f.treeBytes());
    for (GridPrecision p : {GridPrecision::Half, GridPrecision::Fp8, GridPrecision::Fp4}) {
        PrecisionSpec spec;
        spec.precision = p;
        const uint64_t estimate = gridBytesBeforeLoad(info, p);
        EXPECT_LT(estimate, previous) << precisionName(p);
        EXPECT_GE(estimate, quantiseGrid(f, spec).treeBytes()) << precisionName(p);
        previous = estimate;
    }
}

}  // namespace
}  // namespace mirage
