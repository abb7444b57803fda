// Quantised grids encoded as their leaves are read (volume/openvdb_to_nano.h,
// volume/leaf_codec.h): at half, fp8 and fp4 the NanoVDB grid a load makes is byte for byte the
// one NanoVDB's own encoder makes of the loaded float grid (volume/grid_quantise.h), on a
// generated pyro cache (half floats), on the reference cache, on bad values under the voxel
// rule, after an expression; leaves of one value decode exactly, their statistics coded 0; and
// the largest value kept on the way is the decoded grid's own.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <type_traits>

#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "volume/grid_lookup.h"
#include "volume/grid_quantise.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

constexpr GridPrecision kStreamed[] = {GridPrecision::Half, GridPrecision::Fp8, GridPrecision::Fp4};

PrecisionSpec at(GridPrecision p) {
    PrecisionSpec s;
    s.precision = p;
    return s;
}

std::string bytesOf(const FloatGrid& g) {
    const void* data = g.visit([](const auto& grid) { return static_cast<const void*>(&grid); });
    return std::string(static_cast<const char*>(data), size_t(g.treeBytes()));
}

// The same bytes in a grid of their own, its maximum found by reading every decoded value.
FloatGrid maximumReadAfterwards(const FloatGrid& g) {
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(g.treeBytes());
    std::memcpy(buffer.data(), bytesOf(g).data(), g.treeBytes());
    return FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer>(std::move(buffer)), g.name());
}

// Each streamed precision of grid `name` against NanoVDB's encoder on the float load.
void expectStreamedIsNanoVdbs(const std::string& path, const std::string& name) {
    const FloatGrid f = loadFloatGrid(path, name);
    for (GridPrecision p : kStreamed) {
        SCOPED_TRACE(path + " " + name + " at " + precisionName(p));
        const FloatGrid streamed = loadFloatGrid(path, name, p);
        const FloatGrid encoded = quantiseGrid(f, at(p));
        ASSERT_EQ(streamed.precision(), p);
        ASSERT_EQ(streamed.treeBytes(), encoded.treeBytes());
        EXPECT_TRUE(bytesOf(streamed) == bytesOf(encoded));
        EXPECT_EQ(streamed.maxValue(), encoded.maxValue());
        EXPECT_EQ(streamed.maxValue(), maximumReadAfterwards(streamed).maxValue());
        EXPECT_EQ(streamed.sanitizedVoxels(), f.sanitizedVoxels());
        EXPECT_EQ(streamed.activeVoxels(), f.activeVoxels());
        EXPECT_EQ(streamed.treeBytes(), f.treeBytesAt(p));  // only the leaves shrink
    }
}

TEST(StreamedPrecision, SameBytesAsNanoVdbsEncoderOnAPyroCache) {
    const std::string path = test::tempDir() + "/pyro.vdb";
    writeProceduralAsset("pyro", path, 48, 5);
    expectStreamedIsNanoVdbs(path, "density");
    expectStreamedIsNanoVdbs(path, "temperature");
}

TEST(StreamedPrecision, SameBytesAsNanoVdbsEncoderOnTheReferenceCache) {
    MIRAGE_REQUIRE_SHARED(smoke, "vdb/smoke1.vdb");
    expectStreamedIsNanoVdbs(smoke, "density");
}

// Bad values (the voxel rule on the way), inactive values beside active ones, tiles of both
// internal levels, a fog volume and a grid of no stated class. Every leaf holds two values at
// least: on a leaf of one value NanoVDB's encoder converts 0/0 to an integer (see below).
TEST(StreamedPrecision, SameBytesUnderTheVoxelRule) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (const char* cls : {"fog volume", "unknown"}) {
        TestGridSpec spec;
        spec.gridClass = cls;
        spec.voxels = {{0, 0, 0, 1.0},   {1, 0, 0, nan},     {2, 0, 0, -3.0},
                       {3, 0, 0, inf},   {4, 0, 0, 1e12},    {9, 9, 9, 0.5},
                       {-20, 5, 7, 2.0}, {40, 41, 42, -inf}, {41, 41, 42, 3.0}};
        spec.inactiveVoxels = {{5, 0, 0, nan}, {6, 0, 0, -1.0}, {7, 0, 0, 1e11}};
        for (int n = 0; n < 511; ++n) spec.voxels.push_back({16 + n % 8, n / 8 % 8, n / 64, 0.75});
        spec.voxels.push_back({23, 7, 7, 0.25});  // a full leaf of two values
        spec.tiles = {{64, 0, 0, 1, -2.0}, {0, 512, 0, 2, nan}, {300, 0, 0, 2, 0.25}};
        const std::string path = test::tempDir() + "/bad_values.vdb";
        writeTestGrid(path, spec);
        SCOPED_TRACE(cls);
        expectStreamedIsNanoVdbs(path, "density");
    }
}

template <typename Data, typename = void>
struct IsQuantised : std::false_type {};
template <typename Data>
struct IsQuantised<Data, std::void_t<decltype(Data::mQuantum)>> : std::true_type {};

// A leaf of one value has quantum 0: it decodes to that value exactly, and its statistics'
// codes are 0, the bytes x86 makes of NanoVDB's conversion of 0/0 (undefined behaviour, so the
// encoder is not run on it here). Active values of 0.75 filling a leaf, one active zero, and
// −∞ made 0 by the voxel rule.
TEST(StreamedPrecision, LeavesOfOneValueDecodeExactlyWithStatisticsCodedZero) {
    TestGridSpec spec;
    for (int n = 0; n < 512; ++n) spec.voxels.push_back({16 + n % 8, n / 8 % 8, n / 64, 0.75});
    spec.voxels.push_back({33, 1, 1, 0.0});
    spec.voxels.push_back({40, 41, 42, -std::numeric_limits<double>::infinity()});
    const std::string path = test::tempDir() + "/one_valued.vdb";
    writeTestGrid(path, spec);
    const FloatGrid f = loadFloatGrid(path, "density");
    for (GridPrecision p : kStreamed) {
        SCOPED_TRACE(precisionName(p));
        const FloatGrid streamed = loadFloatGrid(path, "density", p);
        ASSERT_EQ(streamed.precision(), p);
        EXPECT_EQ(streamed.maxValue(), 0.75f);
        EXPECT_EQ(streamed.activeVoxels(), f.activeVoxels());
        EXPECT_EQ(streamed.sanitizedVoxels(), 1u);
        const uint32_t leaves = streamed.visit([&](const auto& grid) {
            const auto& tree = grid.tree();
            const auto* leaf = tree.getFirstLeaf();
            for (uint32_t i = 0; i < tree.nodeCount(0); ++i) {
                const auto& data = *leaf[i].data();
                if constexpr (IsQuantised<std::decay_t<decltype(data)>>::value) {
                    EXPECT_EQ(data.mQuantum, 0.0f);
                    EXPECT_EQ(data.mMin + data.mMax + data.mAvg + data.mDev, 0);
                }
                for (uint32_t v = 0; v < 512; ++v) {
                    const nanovdb::Coord ijk = leaf[i].offsetToGlobalCoord(v);
                    EXPECT_EQ(leaf[i].getValue(v), f.grid()->tree().getValue(ijk))
                        << ijk[0] << " " << ijk[1] << " " << ijk[2];
                }
            }
            return tree.nodeCount(0);
        });
        EXPECT_EQ(leaves, 3u);
    }
}

TEST(StreamedPrecision, SameBytesAfterAnExpression) {
    const std::string path = test::tempDir() + "/pyro.vdb";
    writeProceduralAsset("pyro", path, 32, 5);
    const GridExpression e{"@density = clamp(@density * 3 - 0.2, 0, 1);",
                           FileLoc{"test.toml", 3, 1},
                           "'expression' in [volume]",
                           {}};
    const FloatGrid f = loadFloatGrids(path, {"density"}, {e}).front();
    for (GridPrecision p : kStreamed) {
        SCOPED_TRACE(precisionName(p));
        const FloatGrid streamed = loadGridsAt(path, {"density"}, {e}, nullptr, at(p)).front();
        EXPECT_TRUE(bytesOf(streamed) == bytesOf(quantiseGrid(f, at(p))));
    }
}

// fpn is not streamed: loadGridsAt quantises the float load, as before.
TEST(StreamedPrecision, FpnTakesTheFloatGridThroughNanoVdbsEncoder) {
    const std::string path = test::tempDir() + "/pyro.vdb";
    writeProceduralAsset("pyro", path, 32, 5);
    EXPECT_EQ(loadFloatGrid(path, "density", GridPrecision::FpN).precision(), GridPrecision::Float);
    const FloatGrid fpn = loadGridsAt(path, {"density"}, {}, nullptr, at(GridPrecision::FpN))[0];
    ASSERT_EQ(fpn.precision(), GridPrecision::FpN);
    EXPECT_TRUE(bytesOf(fpn) ==
                bytesOf(quantiseGrid(loadFloatGrid(path, "density"), at(GridPrecision::FpN))));
}

}  // namespace
}  // namespace mirage
