// The majorant grid: conservative bounds of σt over each cell (delta tracking is biased
// wherever σt exceeds its majorant), and a DDA that partitions the clipped ray interval
// exactly (free-flight sampling integrates over the segments it reports).
#include "volume/majorant.h"
#include "transport/tracking.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "volume/grid_lookup.h"
#include "volume/grid_quantise.h"
#include "volume/stored_values.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

struct Segment {
    float t0, t1, value;
};

std::vector<Segment> walk(const MajorantGrid& m, const Vec3& o, const Vec3& d, float tMin,
                          float tMax) {
    std::vector<Segment> s;
    m.traverse(o, d, tMin, tMax, [&](float t0, float t1, float v) {
        s.push_back({t0, t1, v});
        return true;
    });
    return s;
}

// The cell containing p (clamped to the grid).
float cellAt(const MajorantGrid& m, const Vec3& p) {
    int c[3];
    const Bounds3& b = m.bounds();
    for (int a = 0; a < 3; ++a) {
        float x = (p[a] - b.lo[a]) / (b.hi[a] - b.lo[a]) * float(m.res(a));
        c[a] = clamp(int(std::floor(x)), 0, m.res(a) - 1);
    }
    return m.cell(c[0], c[1], c[2]);
}

Vec3 uniformIn(Sampler& rng, const Bounds3& b) {
    return b.lo + b.diagonal() * Vec3(rng.get1D(), rng.get1D(), rng.get1D());
}

// For random points, scale × lookup must not exceed the majorant of the point's cell.
void expectConservative(const MajorantGrid& m, const std::vector<const FloatGrid*>& grids,
                        const std::vector<float>& scales, int points) {
    std::vector<FloatGrid::Accessor> accs;
    for (const FloatGrid* g : grids) accs.push_back(g->accessor());
    Sampler rng(17, 0, 0);
    int nonZero = 0;
    for (int n = 0; n < points; ++n) {
        Vec3 p = uniformIn(rng, m.bounds());
        float sigma = 0.f;
        for (size_t i = 0; i < grids.size(); ++i) sigma += scales[i] * grids[i]->sample(accs[i], p);
        nonZero += sigma > 0.f;
        ASSERT_LE(sigma, cellAt(m, p)) << "at " << p.x << ", " << p.y << ", " << p.z;
    }
    EXPECT_GT(nonZero, points / 20);  // the test looked inside the medium, not only around it
}

std::string makeSmoke(int resolution = 40) {
    std::string path = test::tempDir() + "/smoke.vdb";
    writeProceduralAsset("smoke", path, resolution, 3);
    return path;
}

TEST(Majorant, CellsAreRoughlyCubicAndTileTheBounds) {
    Bounds3 b{Vec3(-1.f, 0.f, 2.f), Vec3(0.f, 2.f, 2.5f)};
    MajorantGrid m(b, 64);
    EXPECT_EQ(m.res(0), 32);
    EXPECT_EQ(m.res(1), 64);
    EXPECT_EQ(m.res(2), 16);
    EXPECT_EQ(m.maxValue(), 0.f);
    m.addConstant(0.5f);
    m.addConstant(0.25f);
    EXPECT_EQ(m.cell(31, 63, 15), 0.75f);
    EXPECT_EQ(m.maxValue(), 0.75f);
    MajorantGrid flat(Bounds3{Vec3(0.f), Vec3(1.f, 1.f, 0.f)}, 8);
    EXPECT_EQ(flat.res(2), 1);
}

TEST(Majorant, ConservativeOnSmoke1) {
    MIRAGE_REQUIRE_SHARED(path, "vdb/smoke1.vdb");
    FloatGrid g = loadFloatGrid(path, "density");
    MajorantGrid m(g.objectBounds(), 32);
    m.addGrid(g, 3.f);
    expectConservative(m, {&g}, {3.f}, 200000);
    // Tight where it matters: the largest cell is the grid's maximum, and cells are not all
    // at that maximum.
    EXPECT_NEAR(m.maxValue(), 3.f * g.maxValue(), 1e-4f * m.maxValue());
    int low = 0;
    for (int z = 0; z < m.res(2); ++z)
        for (int y = 0; y < m.res(1); ++y)
            for (int x = 0; x < m.res(0); ++x) low += m.cell(x, y, z) < 0.5f * m.maxValue();
    EXPECT_GT(low, m.res(0) * m.res(1) * m.res(2) / 2);
}

TEST(Majorant, ConservativeOnProceduralSmokeWithTwoComponents) {
    std::string path = makeSmoke();
    FloatGrid density = loadFloatGrid(path, "density");
    FloatGrid temperature = loadFloatGrid(path, "temperature");
    Bounds3 b = density.objectBounds();
    b.expand(temperature.objectBounds());
    MajorantGrid m(b, 16);
    m.addGrid(density, 20.f);
    m.addGrid(temperature, 0.01f);
    m.addConstant(0.1f);
    std::vector<float> scales = {20.f, 0.01f};
    auto accD = density.accessor();
    auto accT = temperature.accessor();
    Sampler rng(23, 0, 0);
    for (int n = 0; n < 100000; ++n) {
        Vec3 p = uniformIn(rng, b);
        float sigma = 20.f * density.sample(accD, p) + 0.01f * temperature.sample(accT, p) + 0.1f;
        ASSERT_LE(sigma, cellAt(m, p));
    }
}

TEST(Majorant, ConservativeWithTilesAndLoneVoxels) {
    // Tiles of both internal levels and lone voxels far apart: the majorant must cover the
    // trilinear footprint of each, one voxel beyond its edge.
    const std::string path = test::tempDir() + "/tiles.vdb";
    TestGridSpec spec;
    spec.voxelSize = 0.05;
    spec.voxels = {{-3, 5, 7, 4.0}, {40, 2, 2, 1.5}};
    spec.tiles = {{8, 8, 8, 1, 2.0}, {128, 0, 0, 2, 0.5}};
    writeTestGrid(path, spec);
    FloatGrid g = loadFloatGrid(path, "density");
    MajorantGrid m(g.objectBounds(), 24);
    m.addGrid(g, 1.f);
    expectConservative(m, {&g}, {1.f}, 200000);
}

// A quantised grid's lookups read decoded values, which can lie above the floats they encode
// (fp4's step is a fifteenth of a leaf's range): the majorant bounds the decoded ones.
TEST(Majorant, ConservativeOverQuantisedGrids) {
    const FloatGrid f = loadFloatGrid(makeSmoke(), "density");
    for (GridPrecision p : {GridPrecision::Fp4, GridPrecision::FpN}) {
        PrecisionSpec spec;
        spec.precision = p;
        spec.relativeTolerance = 0.05f;
        const FloatGrid q = quantiseGrid(f, spec);
        MajorantGrid m(q.objectBounds(), 32);
        m.addGrid(q, 2.f);
        expectConservative(m, {&q}, {2.f}, 100000);
    }
}

// Cells of a few voxels hold the largest value near them, not their leaf's: one hot voxel at
// the end of a row of 1s raises only the cells its own footprint reaches.
TEST(Majorant, CellsHoldTheVoxelsNearThemNotTheirLeafsMaximum) {
    const std::string path = test::tempDir() + "/hot_voxel.vdb";
    TestGridSpec spec;
    spec.voxelSize = 0.05;
    for (int i = 0; i < 16; ++i) spec.voxels.push_back({i, 0, 0, i == 0 ? 10.0 : 1.0});
    writeTestGrid(path, spec);
    FloatGrid g = loadFloatGrid(path, "density");
    MajorantGrid m(g.objectBounds(), 9);  // cells two voxels wide along the row
    m.addGrid(g, 1.f);
    expectConservative(m, {&g}, {1.f}, 200000);
    auto at = [&](double i) {
        const nanovdb::Vec3d p = g.grid()->indexToWorld(nanovdb::Vec3d(i, 0.0, 0.0));
        return cellAt(m, Vec3(float(p[0]), float(p[1]), float(p[2])));
    };
    EXPECT_GE(at(0.0), 10.f);
    // Voxels 4 to 7 share the hot voxel's leaf (0–7) but lie beyond its footprint (−1, 1).
    for (double i : {4.5, 6.5}) {
        EXPECT_GE(at(i), 1.f) << i;
        EXPECT_LE(at(i), 1.001f) << i;
    }
}

// One splat per voxel, as the majorant once did it: each value > 0 onto the cells its footprint
// (i − 1.001, i + 1.001) touches on each axis (an axis-aligned map), maximum per cell.
std::vector<float> splatPerVoxel(const FloatGrid& g, const MajorantGrid& m) {
    const Bounds3& b = m.bounds();
    std::vector<float> cells(size_t(m.res(0)) * m.res(1) * m.res(2), 0.f);
    auto cellIndex = [&](int a, float x) {
        const float c = (x - b.lo[a]) * (1.f / ((b.hi[a] - b.lo[a]) / float(m.res(a))));
        if (!(c > 0.f)) return 0;
        return c >= float(m.res(a)) ? m.res(a) - 1 : int(c);
    };
    const auto& tree = g.grid()->tree();
    const auto* leaf = tree.getFirstLeaf();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i)
        for (uint32_t n = 0; n < 512; ++n) {
            const float v = leaf[i].getValue(n);
            if (!(v > 0.f)) continue;
            const nanovdb::Coord ijk = leaf[i].offsetToGlobalCoord(n);
            int lo[3], hi[3];
            bool inside = true;
            for (int a = 0; a < 3; ++a) {
                nanovdb::Vec3d p0(0.0), p1(0.0);
                p0[a] = ijk[a] - 1.001;
                p1[a] = ijk[a] + 1.001;
                const double w0 = g.grid()->indexToWorld(p0)[a], w1 = g.grid()->indexToWorld(p1)[a];
                lo[a] = cellIndex(a, float(std::min(w0, w1)));
                hi[a] = cellIndex(a, float(std::max(w0, w1)));
                inside = inside && std::max(w0, w1) >= double(b.lo[a]) &&
                         std::min(w0, w1) <= double(b.hi[a]);
            }
            if (!inside) continue;
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) {
                        float& c = cells[(size_t(z) * m.res(1) + y) * m.res(0) + x];
                        c = std::max(c, v);
                    }
        }
    return cells;
}

// The leaves' voxels splatted in groups that share their cells give the cells one splat per
// voxel gave, bit for bit, whether cells are narrower or wider than a leaf.
TEST(Majorant, GroupedSplatsAreTheSplatsOfEachVoxel) {
    const FloatGrid g = loadFloatGrid(makeSmoke(40), "density");
    uint64_t tiles = 0;
    forEachTileValue(g.grid()->tree(), [&](float v, uint64_t) { tiles += v > 0.f; });
    ASSERT_EQ(tiles, 0u);  // the leaves alone hold the medium: the oracle splats leaves only
    for (int res : {3, 7, 13, 64}) {
        SCOPED_TRACE(res);
        MajorantGrid m(g.objectBounds(), res);
        m.addGrid(g, 1.f);
        const std::vector<float> expected = splatPerVoxel(g, m);
        size_t nonZero = 0;
        for (int z = 0; z < m.res(2); ++z)
            for (int y = 0; y < m.res(1); ++y)
                for (int x = 0; x < m.res(0); ++x) {
                    const float e = expected[(size_t(z) * m.res(1) + y) * m.res(0) + x];
                    nonZero += e > 0.f;
                    ASSERT_EQ(m.cell(x, y, z), (1.f + 1e-6f) * e) << x << " " << y << " " << z;
                }
        EXPECT_GT(nonZero, 0u);
    }
}

// The procedural smoke (32³) under a majorant of 12 cells, and a box three times its size about
// it for rays to start in: the walks' tests.
struct SmokeWalks {
    FloatGrid grid;
    MajorantGrid majorant;
    Bounds3 bounds, around;
    Vec3 size;
};

SmokeWalks smokeWalks() {
    SmokeWalks s;
    s.grid = loadFloatGrid(makeSmoke(32), "density");
    s.majorant = MajorantGrid(s.grid.objectBounds(), 12);
    s.majorant.addGrid(s.grid, 1.f);
    s.bounds = s.majorant.bounds();
    s.size = s.bounds.diagonal();
    s.around = {s.bounds.lo - s.size, s.bounds.hi + s.size};
    return s;
}

TEST(Majorant, TraversalPartitionsTheClippedInterval) {
    const SmokeWalks smoke = smokeWalks();
    const MajorantGrid& m = smoke.majorant;
    const Bounds3& b = smoke.bounds;
    const Vec3& size = smoke.size;
    const Bounds3& around = smoke.around;
    const Vec3 axes[6] = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                          Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    Sampler rng(29, 0, 0);
    int hits = 0, misses = 0, axial = 0;
    for (int n = 0; n < 20000; ++n) {
        const int kind = n % 4;
        Vec3 o = kind == 1 ? uniformIn(rng, b) : uniformIn(rng, around);  // 1: starts inside
        Vec3 d;
        if (kind == 2) {
            // Axis-parallel, not unit length, crossing the bounds; every third one along a
            // cell face.
            const int axis = (n / 4) % 6;
            d = axes[axis] * (0.1f + 10.f * rng.get1D());
            const Vec3 inside = uniformIn(rng, b);
            for (int a = 0; a < 3; ++a)
                if (a != axis / 2) o[a] = inside[a];
            if (n % 3 == 0) {
                const int a = (axis / 2 + 1) % 3;
                o[a] = b.lo[a] + float(n % m.res(a)) * (size[a] / float(m.res(a)));
            }
        } else if (kind == 3) {
            // Aimed at a point inside, through cell boundaries: a point on a cell face.
            Vec3 target = uniformIn(rng, b);
            int a = n % 3;
            target[a] = b.lo[a] + std::floor(rng.get1D() * m.res(a)) * (size[a] / m.res(a));
            d = target - o;
        } else {
            d = Vec3(rng.get1D() - 0.5f, rng.get1D() - 0.5f, rng.get1D() - 0.5f) *
                std::exp(6.f * (rng.get1D() - 0.5f));
        }
        const float tMin = rng.get1D() < 0.5f ? 0.f : rng.get1D();
        const float tMax = rng.get1D() < 0.5f ? kInfinity : tMin + 3.f * rng.get1D();
        std::vector<Segment> s = walk(m, o, d, tMin, tMax);

        float t0, t1;
        if (!b.intersect(o, d, tMin, tMax, &t0, &t1) || !(t0 < t1)) {
            EXPECT_TRUE(s.empty());
            ++misses;
            continue;
        }
        ++hits;
        axial += kind == 2;
        ASSERT_FALSE(s.empty());
        ASSERT_EQ(s.front().t0, t0);
        ASSERT_EQ(s.back().t1, t1);
        for (size_t i = 0; i < s.size(); ++i) {
            ASSERT_LT(s[i].t0, s[i].t1);
            if (i > 0) {
                ASSERT_EQ(s[i].t0, s[i - 1].t1);
            }
            // The value is that of the cell the segment crosses (away from rounding at faces).
            const float len = (s[i].t1 - s[i].t0) * length(d);
            if (len > 1e-3f * size.x / m.res(0)) {
                ASSERT_EQ(s[i].value, cellAt(m, o + d * (0.5f * (s[i].t0 + s[i].t1))));
            }
        }
        ASSERT_LE(s.size(), size_t(m.res(0) + m.res(1) + m.res(2)));
    }
    EXPECT_GT(hits, 5000);
    EXPECT_GT(misses, 1000);
    EXPECT_GT(axial, 1000);
}

// Free-flight sampling keeps one walk across a flight's collisions (transport/tracking.cpp):
// moved to a point inside a segment, the walk must go on as a fresh walk from that point would.
TEST(Majorant, AWalkMovedAlongGoesOnAsAFreshOne) {
    const SmokeWalks smoke = smokeWalks();
    const MajorantGrid& m = smoke.majorant;
    const Bounds3& b = smoke.bounds;
    const Vec3& size = smoke.size;
    Sampler rng(31, 0, 0);
    int resumed = 0;
    for (int n = 0; n < 5000; ++n) {
        const Vec3 o = uniformIn(rng, smoke.around);
        const Vec3 d = uniformIn(rng, b) - o;
        MajorantGrid::Walk kept(m, o, d, 0.f, kInfinity);
        MajorantGrid::Walk::Segment s;
        // Stops at random points of the segments, each time against a fresh walk from there.
        while (kept.next(&s)) {
            if (rng.get1D() < 0.5f) {
                kept.advanceTo(s.t1);
                continue;
            }
            const float t = s.t0 + (0.25f + 0.5f * rng.get1D()) * (s.t1 - s.t0);
            if (!(t > s.t0 && t < s.t1) || (s.t1 - s.t0) * length(d) < 1e-3f * size.x) {
                kept.advanceTo(s.t1);
                continue;
            }
            kept.advanceTo(t);
            const std::vector<Segment> fresh = walk(m, o, d, t, kInfinity);
            MajorantGrid::Walk copy = kept;
            for (const Segment& f : fresh) {
                MajorantGrid::Walk::Segment c;
                ASSERT_TRUE(copy.next(&c));
                ASSERT_EQ(c.t0, f.t0);
                ASSERT_EQ(c.t1, f.t1);
                ASSERT_EQ(c.sigmaMaj, f.value);
                copy.advanceTo(c.t1);
            }
            ASSERT_FALSE(copy.next(&s));
            ++resumed;
        }
    }
    EXPECT_GT(resumed, 5000);
}

TEST(Majorant, RaysThatMissCallNothing) {
    MajorantGrid m(Bounds3{Vec3(0.f), Vec3(1.f)}, 8);
    m.addConstant(1.f);
    auto calls = [&](Vec3 o, Vec3 d, float tMin = 0.f, float tMax = kInfinity) {
        return walk(m, o, d, tMin, tMax).size();
    };
    EXPECT_EQ(calls(Vec3(-1.f, 0.5f, 0.5f), Vec3(-1.f, 0.f, 0.f)), 0u);  // pointing away
    EXPECT_EQ(calls(Vec3(-1.f, 2.f, 0.5f), Vec3(1.f, 0.f, 0.f)), 0u);    // parallel, outside
    EXPECT_EQ(calls(Vec3(-1.f, 0.5f, 0.5f), Vec3(1.f, 0.f, 0.f), 0.f, 0.5f), 0u);  // too short
    EXPECT_EQ(calls(Vec3(-1.f, 0.5f, 0.5f), Vec3(1.f, 0.f, 0.f), 2.5f), 0u);       // starts past
    EXPECT_EQ(calls(Vec3(0.5f), Vec3(0.f)), 1u);  // no direction: one span where it stands
    EXPECT_EQ(calls(Vec3(-1.f, 0.5f, 0.5f), Vec3(1.f, 0.f, 0.f)), 8u);
    EXPECT_EQ(walk(MajorantGrid(), Vec3(0.f), Vec3(1.f), 0.f, kInfinity).size(), 0u);
}

TEST(Majorant, TraversalStopsWhenAsked) {
    MajorantGrid m(Bounds3{Vec3(0.f), Vec3(1.f)}, 8);
    int n = 0;
    bool finished = m.traverse(Vec3(-1.f, 0.5f, 0.5f), Vec3(1.f, 0.f, 0.f), 0.f, kInfinity,
                               [&](float, float, float) { return ++n < 3; });
    EXPECT_FALSE(finished);
    EXPECT_EQ(n, 3);
}

}  // namespace
}  // namespace mirage
