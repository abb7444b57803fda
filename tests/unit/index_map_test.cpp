// IndexMap (volume/index_map.h): the grids' object → index transform without fmaf calls where the
// map is diagonal, and NanoVDB's own transform elsewhere. Every lookup's stencil and fractions
// come from it, so it must give the bits of NanoVDB's worldToIndexF.
#include "volume/index_map.h"

#include <gtest/gtest.h>
#include <nanovdb/NanoVDB.h>

#include <cmath>
#include <random>
#include <vector>

namespace mirage {
namespace {

// Points spread over many magnitudes and both signs, as object-space lookups are: inside a small
// cache, kilometres out, and at the origin.
std::vector<nanovdb::Vec3f> testPoints() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> mantissa(-1.f, 1.f);
    std::uniform_int_distribution<int> exponent(-12, 12);
    std::vector<nanovdb::Vec3f> points = {{0.f, 0.f, 0.f}, {-0.f, 1.f, -1.f}};
    for (int i = 0; i < 20000; ++i) {
        nanovdb::Vec3f p;
        for (int a = 0; a < 3; ++a) p[a] = std::ldexp(mantissa(rng), exponent(rng));
        points.push_back(p);
    }
    return points;
}

// Equal as floats (+0 and −0 alike: floor() and the stencil's fractions cannot tell them apart).
void expectSameIndex(const nanovdb::Map& map) {
    const IndexMap fast(map);
    for (const nanovdb::Vec3f& p : testPoints()) {
        const Vec3 a = fast.toIndex(Vec3(p[0], p[1], p[2]));
        const nanovdb::Vec3f b = map.applyInverseMapF(p);
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(a[c], b[c]) << "axis " << c << " at (" << p[0] << ", " << p[1] << ", " << p[2]
                                  << ")";
    }
}

TEST(IndexMap, UniformVoxelsGiveNanoVdbsBits) {
    for (double dx : {0.1, 0.37, 1.0, 2.5e-3, 40.0}) {
        nanovdb::Map map;
        map.set(dx, nanovdb::Vec3d(-3.2, 0.25, 17.0), 1.0);
        expectSameIndex(map);
    }
}

TEST(IndexMap, PerAxisVoxelSizesGiveNanoVdbsBits) {
    const double mat[3][3] = {{0.1, 0, 0}, {0, 0.3, 0}, {0, 0, 0.07}};
    const double inv[3][3] = {{1 / 0.1, 0, 0}, {0, 1 / 0.3, 0}, {0, 0, 1 / 0.07}};
    nanovdb::Map map;
    map.set(mat, inv, nanovdb::Vec3d(1.5, -2.0, 0.125), 1.0);
    expectSameIndex(map);
}

TEST(IndexMap, RotatedMapsKeepNanoVdbsTransform) {
    // 30° about z with voxel size 0.2: the full matrix product, NanoVDB's own.
    const double c = std::cos(M_PI / 6) * 0.2, s = std::sin(M_PI / 6) * 0.2;
    const double mat[3][3] = {{c, s, 0}, {-s, c, 0}, {0, 0, 0.2}};
    const double k = 1.0 / 0.04;  // the inverse of a scaled rotation: its transpose / scale²
    const double inv[3][3] = {{c * k, -s * k, 0}, {s * k, c * k, 0}, {0, 0, 5.0}};
    nanovdb::Map map;
    map.set(mat, inv, nanovdb::Vec3d(0.5, 0.5, 0.5), 1.0);
    expectSameIndex(map);
    // And it is a rotation: the point one voxel along the rotated x axis is index (1, 0, 0).
    const Vec3 i = IndexMap(map).toIndex(Vec3(0.5f + float(c), 0.5f + float(s), 0.5f));
    EXPECT_NEAR(i[0], 1.f, 1e-5f);
    EXPECT_NEAR(i[1], 0.f, 1e-5f);
}

}  // namespace
}  // namespace mirage
