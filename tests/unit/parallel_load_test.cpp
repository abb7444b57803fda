// The parallel read of OpenVDB grids (volume/openvdb_read.h): the NanoVDB grid a load makes is
// byte for byte the one OpenVDB's whole-grid reader and NanoVDB's converter made before, on the
// reference caches in ../shared/data and on a generated pyro cache (half floats, a velocity
// grid at twice the voxel size); a truncated cache is one clear error naming the file.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

std::string bytesOf(const void* data, uint64_t size) {
    return std::string(static_cast<const char*>(data), size_t(size));
}

// Every scalar grid named, loaded by Mirage, against the whole-grid read.
void expectSameScalarGrids(const std::string& path, const std::vector<std::string>& names) {
    for (const std::string& name : names) {
        SCOPED_TRACE(path + " " + name);
        const FloatGrid loaded = loadFloatGrid(path, name);
        const std::string eager = eagerNanoVdbForTest(path, name);
        ASSERT_EQ(loaded.grid()->gridSize(), eager.size());
        EXPECT_TRUE(bytesOf(loaded.grid(), loaded.grid()->gridSize()) == eager);
        EXPECT_GT(loaded.activeVoxels(), 0u);
    }
}

TEST(ParallelLoad, SameGridsAsAWholeReadOnTheReferenceCaches) {
    MIRAGE_REQUIRE_SHARED(smoke, "vdb/smoke1.vdb");
    MIRAGE_REQUIRE_SHARED(pair, "vdb/density_and_heat.vdb");
    expectSameScalarGrids(smoke, {"density"});
    std::vector<std::string> names;
    for (const GridInfo& g : inspectVdbFile(pair).grids) names.push_back(g.name);
    expectSameScalarGrids(pair, names);
}

TEST(ParallelLoad, SameGridsAsAWholeReadOnAPyroCache) {
    const std::string dir = test::tempDir();
    const std::string path = dir + "/pyro.vdb";
    writeProceduralAsset("pyro", path, 48, 5);
    const VdbFileInfo info = inspectVdbFile(path);
    ASSERT_EQ(info.grids.size(), 3u);
    EXPECT_EQ(info.grids[0].valueType, "half");  // stored as 16-bit floats
    EXPECT_EQ(info.grids[2].name, "vel");
    EXPECT_DOUBLE_EQ(info.grids[2].voxelSize.x, 2.0 * info.grids[0].voxelSize.x);
    expectSameScalarGrids(path, {"density", "temperature"});

    const VectorGrid vel = loadVectorGrid(path, "vel");
    const std::string eager = eagerNanoVdbForTest(path, "vel");
    ASSERT_EQ(vel.grid()->gridSize(), eager.size());
    EXPECT_TRUE(bytesOf(vel.grid(), vel.grid()->gridSize()) == eager);
}

TEST(ParallelLoad, TruncatedPyroCacheIsOneErrorNamingTheFile) {
    const std::string dir = test::tempDir();
    const std::string path = dir + "/pyro.vdb";
    writeProceduralAsset("pyro", path, 32, 5);
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t n : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 1}) {
        const std::string cut = dir + "/pyro_" + std::to_string(n) + ".vdb";
        std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(n));
        for (const char* grid : {"density", "temperature"}) {
            SCOPED_TRACE(cut + " " + grid);
            try {
                loadFloatGrid(cut, grid);
                ADD_FAILURE() << "a truncated file loaded";
            } catch (const MirageError& e) {
                const std::string what = e.what();
                EXPECT_NE(what.find(cut), std::string::npos) << what;
                EXPECT_NE(what.find("truncated"), std::string::npos) << what;
                EXPECT_LT(what.size(), 400u) << what;
            }
        }
    }
}

}  // namespace
}  // namespace mirage
