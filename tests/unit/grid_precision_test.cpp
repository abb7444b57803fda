// Quantised grids (volume/grid_precision.h, volume/grid_quantise.h): a lookup is NanoVDB's own
// decode bit for bit, every decoded voxel and lookup lies within half a quantisation step of the
// float one (the documented bound, from the codec's bit width), the tree's size at every
// precision is exact from its leaf count, a quantised grid keeps no float dense copy, and the
// scene key `precision` is read, cached by precision and refused with one message when wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "film/color.h"
#include "scene/scene.h"
#include "test_grids.h"
#include "test_support.h"
#include "volume/grid_cache.h"
#include "volume/grid_lookup.h"
#include "volume/grid_quantise.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

constexpr GridPrecision kQuantised[] = {GridPrecision::Half, GridPrecision::Fp8, GridPrecision::Fp4,
                                        GridPrecision::FpN};

// Uneven values (a golden-ratio sequence, rising along x) over a few leaves, an inactive voxel
// that stores a value, and a tile.
std::string writeUneven() {
    TestGridSpec spec;
    spec.voxelSize = 0.05;
    spec.origin = Vec3d(-0.3, 0.1, 0.7);
    for (int n = 0; n < 20 * 11 * 12; ++n) {
        const int i = n % 20 - 6, j = n / 20 % 11, k = n / 220 - 3;
        spec.voxels.push_back({i, j, k, (0.05 + std::fmod(0.618034 * n, 1.0)) * (1.0 + 0.1 * i)});
    }
    spec.inactiveVoxels.push_back({13, 10, 0, 0.75});
    spec.tiles.push_back({24, 0, 0, 1, 1.25});
    const std::string path = test::tempDir() + "/uneven.vdb";
    writeTestGrid(path, spec);
    return path;
}

// Points over the grid's bounds and a little beyond.
std::vector<Vec3> pointsAround(const FloatGrid& g, int count) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    const Vec3 lo = g.objectBounds().lo - Vec3(0.1f), hi = g.objectBounds().hi + Vec3(0.1f);
    std::vector<Vec3> p;
    for (int n = 0; n < count; ++n)
        p.emplace_back(lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y),
                       lo.z + u(rng) * (hi.z - lo.z));
    return p;
}

PrecisionSpec at(GridPrecision p) {
    PrecisionSpec s;
    s.precision = p;
    return s;
}

TEST(GridPrecision, QuantisedLookupIsNanoVdbsOwnDecode) {
    const FloatGrid f = loadFloatGrid(writeUneven(), "density");
    for (GridPrecision p : kQuantised) {
        const FloatGrid q = quantiseGrid(f, at(p));
        ASSERT_EQ(q.precision(), p);
        const auto acc = q.accessor();
        q.visit([&](const auto& g) {
            const IndexMap map(g.map());
            auto nano = g.getAccessor();
            auto sampler = nanovdb::createSampler<1, decltype(nano), false>(nano);
            for (const Vec3& x : pointsAround(q, 50000)) {
                const Vec3 i = map.toIndex(x);
                const float ours = q.sample(acc, x),
                            theirs = sampler(nanovdb::Vec3f(i.x, i.y, i.z));
                ASSERT_TRUE(sameBits(ours, theirs))
                    << precisionName(p) << ": " << ours << " against NanoVDB's " << theirs;
            }
        });
    }
}

// Every decoded voxel, and so every lookup (a convex combination of them), within half a step
// of the float: quantisationBound, with a relative 1e-6 for float rounding in the decode.
TEST(GridPrecision, LookupsWithinHalfAQuantisationStep) {
    const FloatGrid f = loadFloatGrid(writeUneven(), "density");
    const auto facc = f.accessor();
    for (GridPrecision p : kQuantised) {
        for (float tolerance : {1e-3f, 2e-2f}) {
            PrecisionSpec spec = at(p);
            spec.relativeTolerance = tolerance;
            const FloatGrid q = quantiseGrid(f, spec);
            const float bound = quantisationBound(spec, f.maxValue()) + 1e-6f * f.maxValue();
            const auto qacc = q.accessor();
            float worst = 0.f;
            for (const Vec3& x : pointsAround(f, 50000))
                worst = std::max(worst, std::abs(q.sample(qacc, x) - f.sample(facc, x)));
            EXPECT_LE(worst, bound) << precisionName(p) << " tolerance " << tolerance;
            // The bound is the codec's, not a loose one: fp4 comes within a factor of 2 of it.
            if (p == GridPrecision::Fp4) {
                EXPECT_GT(worst, 0.5f * bound);
            }
            if (p != GridPrecision::FpN) break;
        }
    }
    EXPECT_FLOAT_EQ(quantisationBound(at(GridPrecision::Fp8), 510.f), 1.f);
    EXPECT_EQ(quantisationBound(at(GridPrecision::Float), 510.f), 0.f);
}

TEST(GridPrecision, TreeBytesAtEveryPrecisionAreExactAndNoDenseCopyIsKept) {
    const FloatGrid f = loadFloatGrid(writeUneven(), "density");
    ASSERT_GT(f.denseBytes(), 0u);
    for (GridPrecision p : kQuantised) {
        const FloatGrid q = quantiseGrid(f, at(p));
        EXPECT_EQ(q.denseBytes(), 0u) << precisionName(p);
        EXPECT_EQ(q.leafCount(), f.leafCount());
        EXPECT_EQ(q.treeBytesAt(p), q.treeBytes());
        if (p == GridPrecision::FpN) {  // its leaves vary: bounded by 16 bits, and no way back
            EXPECT_LE(q.treeBytes(), f.treeBytesAt(p));
            EXPECT_EQ(q.treeBytesAt(GridPrecision::Float), 0u);
        } else {
            EXPECT_EQ(q.treeBytes(), f.treeBytesAt(p)) << precisionName(p);
            EXPECT_EQ(q.treeBytesAt(GridPrecision::Float), f.treeBytes());
        }
        EXPECT_LT(q.treeBytes(), f.treeBytes());
    }
}

// A scene whose volume reads `fog.vdb` at `precision` (a TOML value, e.g. "\"fp8\"").
std::string writeScene(const std::string& dir, const std::string& keys) {
    test::makeFogSphere(dir);
    std::ofstream(dir + "/scene.toml")
        << "[film]\nresolution = [8, 8]\n[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\n"
           "[[volume]]\nfile = \"fog.vdb\"\n"
        << keys << "\n[[light]]\ntype = \"sun\"\ndirection = [0, -1, 0]\nirradiance = 1\n";
    return dir + "/scene.toml";
}

// What `mirage info` says of the scene: its exit code 1 and its one line of error.
std::string infoError(const std::string& scene) {
    std::string out;
    EXPECT_EQ(test::runMirage("info '" + scene + "'", &out), 1) << out;
    return out;
}

TEST(GridPrecision, SceneKeyLoadsTheGridsAtItsPrecisionCachedByIt) {
    const std::string dir = test::tempDir();
    static ColorPipeline color;
    GridCache cache;
    LoadOptions options;
    options.grids = &cache;
    const std::string fp8 = writeScene(dir, "precision = \"fp8\"");
    Scene s = loadScene(fp8, options, color);
    const FloatGrid& g = s.render.media[0]->binding().grids()[0];
    EXPECT_EQ(g.precision(), GridPrecision::Fp8);
    EXPECT_EQ(s.volumes[0].precision.precision, GridPrecision::Fp8);
    loadScene(fp8, options, color);
    EXPECT_EQ(cache.reads(), 1u);  // the same precision: served from the cache
    Scene f = loadScene(writeScene(dir, ""), options, color);
    EXPECT_EQ(f.render.media[0]->binding().grids()[0].precision(), GridPrecision::Float);
    EXPECT_EQ(cache.reads(), 2u);  // another precision: read again
}

TEST(GridPrecision, BadValuesAreOneMessageNamingTheKey) {
    const std::string dir = test::tempDir();
    std::string e = infoError(writeScene(dir, "precision = \"fp5\""));
    EXPECT_NE(e.find("'precision' in"), std::string::npos) << e;
    EXPECT_NE(e.find("unknown precision 'fp5'; expected float, half, fp8, fp4 or fpn"),
              std::string::npos)
        << e;
    EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
    e = infoError(writeScene(dir, "precision = \"fp8\"\nprecision_tolerance = 0.01"));
    EXPECT_NE(e.find("'precision_tolerance' in"), std::string::npos) << e;
    EXPECT_NE(e.find("only precision = \"fpn\" takes a tolerance"), std::string::npos) << e;
    e = infoError(writeScene(dir, "precision = \"fpn\"\nprecision_tolerance = 2"));
    EXPECT_NE(e.find("'precision_tolerance' in"), std::string::npos) << e;
}

}  // namespace
}  // namespace mirage
