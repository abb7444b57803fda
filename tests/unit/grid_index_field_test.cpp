// The gridded index field (medium/grid_index_field.h): ∇n equals finite differences of n, is
// continuous across voxel faces (the point of the tricubic B-spline), the per-brick bounds hold
// and are zero away from a hot blob (straight chords there), a grid of the linear profile gives
// the exact catenary, and a NanoVDB grid copies into the dense form.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/rng.h"
#include "medium/grid_index_field.h"
#include "medium/linear_profile_path.h"
#include "test_support.h"
#include "transport/curved_path.h"

namespace mirage {
namespace {

// A 24³ grid of 0.1 m voxels: ambient 0 with a hot blob of up to 600 K above ambient.
DenseScalarGrid hotBlob() {
    DenseScalarGrid g;
    g.nx = g.ny = g.nz = 24;
    g.voxelSize = 0.1;
    g.origin = Vec3d(-1.15, 0.05, -1.15);
    g.values.resize(24 * 24 * 24);
    for (int k = 0; k < 24; ++k)
        for (int j = 0; j < 24; ++j)
            for (int i = 0; i < 24; ++i) {
                const double r2 = (i - 11.5) * (i - 11.5) + (j - 8) * (j - 8) + (k - 11.5) * (k - 11.5);
                // Rough on purpose: a voxel-scale ripple makes trilinear gradients jump.
                g.values[(size_t(k) * 24 + j) * 24 + i] =
                    r2 < 36 ? float(600 * (1 - r2 / 36) * (1 + 0.2 * ((i + j + k) % 2))) : 0.f;
            }
    return g;
}

GridIndexSettings hotAir() {
    GridIndexSettings s;
    s.temperatureOffset = 288.15;  // ambient air
    return s;
}

TEST(GridIndexField, GradientMatchesFiniteDifferences) {
    const GridIndexField f(hotBlob(), hotAir());
    Sampler rng(7, 0, 0);
    int nonZero = 0;
    for (int s = 0; s < 200; ++s) {
        const Vec3d x(-0.8 + 1.6 * rng.get1Dd(), 0.2 + 1.2 * rng.get1Dd(),
                      -0.8 + 1.6 * rng.get1Dd());
        double n;
        Vec3d g;
        f.eval(x, 550, &n, &g);
        // Fourth-order central differences: n − 1 ~ 3e−4 carries 1e−16 of rounding, so the
        // quotient has ~1e−13 of noise at a 1 mm step (and more where the spline's third
        // derivative jumps, at the blob's edge): 2e−12 is tiny against |∇n| inside the blob.
        const double e = 1e-3;
        for (int a = 0; a < 3; ++a) {
            Vec3d dx(0.0);
            dx[a] = e;
            auto at = [&](double m) { return f.index(x + dx * m, 550); };
            const double fd = (8 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12 * e);
            EXPECT_NEAR(g[a], fd, 1e-4 * std::abs(fd) + 2e-12) << "axis " << a;
        }
        if (length(g) > 0) ++nonZero;
    }
    EXPECT_GT(nonZero, 50);
}

TEST(GridIndexField, GradientIsContinuousAcrossVoxelFaces) {
    const DenseScalarGrid grid = hotBlob();
    const GridIndexField f(grid, hotAir());
    double largestJump = 0, largestGradient = 0;
    // Crossing each x face of the cells along a line through the blob.
    for (int i = 4; i < 20; ++i) {
        const Vec3d face(grid.origin.x + i * grid.voxelSize, 0.9, 0.03);
        double n0, n1;
        Vec3d g0, g1;
        f.eval(face - Vec3d(1e-9, 0, 0), 550, &n0, &g0);
        f.eval(face + Vec3d(1e-9, 0, 0), 550, &n1, &g1);
        largestJump = std::max(largestJump, length(g1 - g0));
        largestGradient = std::max(largestGradient, length(g0));
    }
    ASSERT_GT(largestGradient, 1e-5);
    // C¹ gradient: a jump over 2e−9 m is of the order of |∇∇n|·2e−9 ≪ |∇n|.
    EXPECT_LT(largestJump, 1e-6 * largestGradient);
}

TEST(GridIndexField, BrickBoundsHoldAndVanishAwayFromTheBlob) {
    const GridIndexField f(hotBlob(), hotAir());
    Sampler rng(11, 0, 0);
    for (int s = 0; s < 2000; ++s) {
        const Vec3d x(-1.4 + 2.8 * rng.get1Dd(), -0.2 + 2.8 * rng.get1Dd(),
                      -1.4 + 2.8 * rng.get1Dd());
        double n;
        Vec3d g;
        f.eval(x, 550, &n, &g);
        EXPECT_LE(length(g), f.gradientBound(x, x) * (1 + 1e-12)) << x.x << " " << x.y;
    }
    // The blob has radius 0.6 m around (0, 0.85, 0); a box at a corner of the grid is calm.
    EXPECT_EQ(f.gradientBound(Vec3d(-1.4, 2.0, -1.4), Vec3d(-1.0, 2.5, -1.0)), 0.0);
    EXPECT_GT(f.gradientBound(Vec3d(-0.1, 0.8, -0.1), Vec3d(0.1, 0.9, 0.1)), 0.0);
    // A ray far from the blob is straight all the way; one aimed at it stops being straight
    // before the blob's edge and not before the calm bricks end.
    EXPECT_EQ(f.straightDistance(Vec3d(-3, 2.4, -1.3), Vec3d(1, 0, 0), 10.0), 10.0);
    const double s = f.straightDistance(Vec3d(-3, 0.85, 0), Vec3d(1, 0, 0), 10.0);
    EXPECT_GT(s, 3 - 1.6);  // the brick grid starts 0.4 m beyond the 2.4 m grid
    EXPECT_LT(s, 3 - 0.6);
    // And the stepper takes the calm stretch as one chord.
    CurvedPathSettings set;
    set.tolerance = 1e-8;
    const CurvedPathResult r =
        traceCurvedPath(f, Vec3d(-3, 0.6, 0), Vec3d(1, 0, 0), 550, 6.0, set);
    EXPECT_GE(r.straightChords, 2);  // in and out
    EXPECT_FALSE(r.capped);
    EXPECT_LT(r.end.r.y, 0.6);  // light bends away from hot (low-n) air: below the blob, down
}

TEST(GridIndexField, LinearIndexGridGivesTheExactCatenary) {
    // Cubic B-splines reproduce linear functions: a grid of n = 1 + k·y is the linear profile
    // exactly, two voxels in from the faces.
    const double k = 0.05, h = 0.25;
    DenseScalarGrid g;
    g.nx = g.ny = g.nz = 40;
    g.voxelSize = h;
    g.values.resize(40 * 40 * 40);
    for (int kk = 0; kk < 40; ++kk)
        for (int j = 0; j < 40; ++j)
            for (int i = 0; i < 40; ++i) g.values[(size_t(kk) * 40 + j) * 40 + i] = float(1 + k * j * h);
    g.background = 1;
    GridIndexSettings s;
    s.quantity = GridIndexSettings::Quantity::Index;
    const GridIndexField f(g, s);
    const Vec3d o(1, 2, 1), d = normalize(Vec3d(1, 0.3, 0.5));
    CurvedPathSettings set;
    set.tolerance = 1e-10;
    const CurvedPathResult r = traceCurvedPath(f, o, d, 550, 6.0, set);
    const LinearProfilePath ex = exactLinearProfilePath(1.0, k, Vec3d(0, 1, 0), o, d, 6.0);
    // float samples: n carries ~1e−7 of rounding, so ∇n does too.
    EXPECT_LT(length(r.end.r - ex.endPoint), 1e-5);
    EXPECT_NEAR(r.end.opl, ex.opticalPathLength, 1e-5);
}

TEST(GridIndexField, CopiesANanoVdbGridAndRejectsNonPositiveTemperatures) {
    const FloatGrid grid = test::makeGrid([](int i, int j, int k) { return float(1 + i + 2 * j + 3 * k); },
                                          0, 5, 0.2, Vec3d(1, 0, 0), "temperature");
    const DenseScalarGrid d = denseFromFloatGrid(grid, 0.f);
    ASSERT_EQ(d.nx, 6);
    EXPECT_NEAR(d.voxelSize, 0.2, 1e-12);
    EXPECT_EQ(d.at(2, 3, 4), float(1 + 2 + 6 + 12));
    GridIndexSettings cold;  // offset 0: T = value, and the background 0 K is not a temperature
    EXPECT_THROW((void)GridIndexField(d, cold), MirageError);
}

}  // namespace
}  // namespace mirage
