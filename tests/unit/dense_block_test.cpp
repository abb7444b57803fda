// The dense copy of a small grid (volume/dense_block.h): lookups through it have the tree's bits
// everywhere, inactive voxels and tiles included, and a wide sparse grid keeps its tree alone.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>
#include <random>

#include "test_grids.h"
#include "test_support.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

// Equal bits, so that −0 against +0 or a different NaN would show.
bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// A lumpy block of active voxels, inactive voxels that store values, and an active 8³ tile
// apart from them, in a grid whose index origin is off the object origin.
TestGridSpec lumpySpec() {
    TestGridSpec spec;
    spec.voxelSize = 0.05;
    spec.origin = Vec3d(-0.3, 0.1, 0.7);
    for (int i = -6; i < 14; ++i)
        for (int j = 0; j < 11; ++j)
            for (int k = -3; k < 9; ++k)
                if ((i * 7 + j * 3 + k) % 5 != 0)
                    spec.voxels.push_back({i, j, k, 0.1 + 0.37 * ((i * i + 3 * j + k * k) % 11)});
    spec.inactiveVoxels.push_back({-6, 0, -3 + 5, 2.5});
    spec.inactiveVoxels.push_back({13, 10, 0, 0.75});
    spec.tiles.push_back({24, 0, 0, 1, 1.25});  // voxels 24..31 along x
    return spec;
}

TEST(DenseBlock, LookupsHaveTheTreesBitsEverywhere) {
    const std::string dir = test::tempDir();
    writeTestGrid(dir + "/lumpy.vdb", lumpySpec());
    const FloatGrid dense = loadFloatGrid(dir + "/lumpy.vdb", "density");
    const FloatGrid tree = dense.treeOnly();
    ASSERT_GT(dense.denseBytes(), 0u);
    EXPECT_EQ(tree.denseBytes(), 0u);
    EXPECT_EQ(dense.treeBytes(), tree.treeBytes());
    EXPECT_EQ(dense.memoryBytes(), tree.memoryBytes() + dense.denseBytes());
    // Points over the object bounds and a voxel beyond, where the copy ends and the tree answers.
    const Bounds3 b = dense.objectBounds();
    const Vec3 margin(0.1f);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    const auto acc = dense.accessor();
    int nonZero = 0;
    for (int n = 0; n < 200000; ++n) {
        const Vec3 lo = b.lo - margin, hi = b.hi + margin;
        const Vec3 p(lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y),
                     lo.z + u(rng) * (hi.z - lo.z));
        const float a = dense.sample(acc, p), r = tree.sample(acc, p);
        ASSERT_TRUE(sameBits(a, r))
            << a << " against the tree's " << r << " at " << p.x << ", " << p.y << ", " << p.z;
        nonZero += a != 0.f;
    }
    EXPECT_GT(nonZero, 10000);
}

TEST(DenseBlock, SameCopyForAnyThreadCount) {
    const std::string dir = test::tempDir();
    writeTestGrid(dir + "/lumpy.vdb", lumpySpec());
    std::vector<float> values[2];
    for (int t = 0; t < 2; ++t) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(t + 1));
        const FloatGrid g = loadFloatGrid(dir + "/lumpy.vdb", "density");
        const auto acc = g.accessor();
        for (int i = 0; i < 4000; ++i) {
            const float f = float(i) / 4000.f;
            values[t].push_back(g.sample(acc, Vec3(-0.6f + f, 0.1f + 0.5f * f, 0.5f + 0.6f * f)));
        }
    }
    EXPECT_EQ(values[0], values[1]);
}

TEST(DenseBlock, WideSparseGridsKeepTheTreeAlone) {
    // Two voxels 4000 voxels apart on every axis: a dense box of 256 GB.
    TestGridSpec spec;
    spec.voxels.push_back({0, 0, 0, 1.0});
    spec.voxels.push_back({4000, 4000, 4000, 2.0});
    const std::string dir = test::tempDir();
    writeTestGrid(dir + "/wide.vdb", spec);
    const FloatGrid g = loadFloatGrid(dir + "/wide.vdb", "density");
    EXPECT_EQ(g.denseBytes(), 0u);
    const auto acc = g.accessor();
    EXPECT_FLOAT_EQ(g.sample(acc, Vec3(400.f, 400.f, 400.f)), 2.f);  // voxel centre, h = 0.1
}

TEST(DenseBlock, BudgetIsSmallOrNearTheTreesSize) {
    constexpr uint64_t MiB = uint64_t(1) << 20;
    EXPECT_TRUE(denseCopyFits(64 * MiB, 1 * MiB));    // small: always
    EXPECT_FALSE(denseCopyFits(65 * MiB, 16 * MiB));  // larger than 4× the tree
    EXPECT_TRUE(denseCopyFits(400 * MiB, 100 * MiB));
    EXPECT_FALSE(denseCopyFits(1025 * MiB, 1024 * MiB));  // never above 1 GiB
}

}  // namespace
}  // namespace mirage
