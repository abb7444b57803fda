// The step cap near surfaces (transport/surface_step_cap.h) against the exact path in
// n = n0 + k·y (medium/linear_profile_path.h): where a path bends away from a plane it meets at
// a shallow angle, or grazes, the chord that crosses is short, and its hit is the path's to
// within the stated bound; without the cap, the error controller's long chords put the hit
// centimetres off, or miss the graze.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "medium/index_field.h"
#include "medium/linear_profile_path.h"
#include "transport/curved_tracking.h"
#include "transport/surface_step_cap.h"

namespace mirage {
namespace {

const Vec3d kYAxis(0, 1, 0);

// The exact path's first arc length at which it crosses y = yPlane, by bisection on [0, lEnd],
// over which its height is monotonic.
double exactArcTo(double k, const Vec3d& o, const Vec3d& d, double yPlane, double lEnd) {
    const bool rising = d.y > 0;
    double lo = 0, hi = lEnd;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double y = exactLinearProfilePath(1.0, k, kYAxis, o, d, mid).endPoint.y;
        ((rising ? y < yPlane : y > yPlane) ? lo : hi) = mid;
    }
    return lo;
}

struct Walk {
    bool hit = false;
    Vec3d p;
    int64_t chords = 0;
};

// The chord walk from o along d in n = 1 + k·y against the plane y = yPlane, with or without the
// cap near surfaces.
Walk walkToPlane(double k, const Vec3d& o, const Vec3d& d, double yPlane, bool cap,
                 double maxStep = std::numeric_limits<double>::infinity()) {
    const LinearIndexField field(1.0, k);
    CurvedPathSettings set;
    set.tolerance = 1e-9;
    set.maxStep = maxStep;
    if (cap)
        set.stepCap = surfaceStepCap(&field, set.tolerance, [yPlane](const Vec3d& r,
                                                                     const Vec3d& dir) {
            const double t = (yPlane - r.y) / dir.y;
            return t > 0 ? t : std::numeric_limits<double>::infinity();
        });
    const ChordSurfaceTest plane = [&](const Ray& chord, float tMax) {
        if (chord.d.y == 0.f) return kInfinity;
        const float t = (float(yPlane) - chord.o.y) / chord.d.y;
        return t > 0.f && t < tMax ? t : kInfinity;
    };
    const CurvedWalkEnd end =
        walkCurvedChords(CurvedWalk{field, set, 20.f, plane}, Ray{Vec3(o), Vec3(d)}, 550,
                         [](const CurvedChord&, CurvedWalkEnd*) { return true; });
    EXPECT_TRUE(std::isfinite(end.p.x) && std::isfinite(end.p.y) && std::isfinite(end.p.z));
    return {end.kind == CurvedWalkEnd::Kind::Surface, Vec3d(end.p), end.chords};
}

TEST(SurfaceStepCap, CapIsTheTangentDistanceShortOfTheFloor) {
    const LinearIndexField field(1.0, 0.05);
    double t = 10.0;
    const auto cap = surfaceStepCap(&field, 1e-6, [&](const Vec3d&, const Vec3d&) { return t; });
    // h_floor = sqrt(8·tol·n/|∇n|) at y = 0: a chord that long stands 1e−6 m off the path.
    const double floor = std::sqrt(8 * 1e-6 * 1.0 / 0.05);
    EXPECT_NEAR(cap(Vec3d(0, 0, 0), Vec3d(1, 0, 0)), 10.0 - 0.5 * floor, 1e-12);
    t = 0.5 * floor;
    EXPECT_NEAR(cap(Vec3d(0, 0, 0), Vec3d(1, 0, 0)), floor, 1e-15);
    t = std::numeric_limits<double>::infinity();
    EXPECT_EQ(cap(Vec3d(0, 0, 0), Vec3d(1, 0, 0)), 0.0) << "no surface ahead: no cap";
    const LinearIndexField flat(1.0, 0.0);
    t = 1.0;
    EXPECT_EQ(surfaceStepCap(&flat, 1e-6, [&](const Vec3d&, const Vec3d&) { return t; })(
                  Vec3d(0, 0, 0), Vec3d(1, 0, 0)),
              0.0)
        << "straight paths need no cap";
}

TEST(SurfaceStepCap, ShallowHitOnAPathBendingAwayIsThePaths) {
    // n = 1 + 0.05·y bends paths up (R = n/|∇n| ≈ 20 m): from 1 m, 0.4 rad down, a path meets
    // the ground at ~0.26 rad (cos α = n(1 m)·cos 0.4 / n(0)), curving away from it — an
    // inferior mirage's ray that still reaches the road.
    const double k = 0.05;
    const Vec3d o(0, 1, 0), d = normalize(Vec3d(1, -std::tan(0.4), 0));
    const double lBottom = -(1.0 + k * o.y) * d.y / k;  // u = n·d_y + k·l = 0: the lowest point
    const double l = exactArcTo(k, o, d, 0.0, lBottom);
    const Vec3d exact = exactLinearProfilePath(1.0, k, kYAxis, o, d, l).endPoint;
    const Walk with = walkToPlane(k, o, d, 0.0, true), without = walkToPlane(k, o, d, 0.0, false);
    ASSERT_TRUE(with.hit);
    ASSERT_TRUE(without.hit);
    const double eWith = length(with.p - exact), eWithout = length(without.p - exact);
    std::printf("shallow hit: error %.3g m in %lld chords with the cap, %.3g m in %lld without\n",
                eWith, (long long)with.chords, eWithout, (long long)without.chords);
    // With the cap: the crossing chord is h_floor long (sagitta ≤ tolerance): the error is the
    // float plane intersection's (~1e−7 m at 1 m) over sin α.
    EXPECT_LT(eWith, 1e-5);
    EXPECT_LT(eWith, 0.01 * eWithout);
}

TEST(SurfaceStepCap, GrazeDeeperThanTheToleranceIsFound) {
    // n = 1 − 0.05·y bends a path that rises at 0.1 rad back down: its apex is at
    // y = (1 − cos 0.1)/0.05, R ≈ 19.9 m. A ceiling ε below the apex is touched over a width of
    // 2√(2Rε); a 0.1 m chord stands up to 6.3e−5 m below the arc and misses shallower grazes.
    const double k = -0.05, theta = 0.1, C = std::cos(theta), R = C / 0.05;
    const Vec3d o(0, 0, 0), d(std::cos(theta), std::sin(theta), 0);
    const double yApex = (1 - C) / 0.05, lApex = std::sin(theta) / 0.05;  // u = sin θ + k·l = 0
    int missedWithout = 0;
    for (double eps : {1e-6, 3e-6, 1e-5, 3e-5}) {
        const double yPlane = yApex - eps;
        const Vec3d exact =
            exactLinearProfilePath(1.0, k, kYAxis, o, d, exactArcTo(k, o, d, yPlane, lApex))
                .endPoint;
        const Walk with = walkToPlane(k, o, d, yPlane, true, 0.1);
        const Walk without = walkToPlane(k, o, d, yPlane, false, 0.1);
        missedWithout += !without.hit;
        ASSERT_TRUE(with.hit) << "graze " << eps << " m deep";
        const double eWith = length(with.p - exact);
        std::printf("graze %.0e m deep: with the cap hit %.3g m from the exact crossing (%lld "
                    "chords); without: %s %.3g m\n",
                    eps, eWith, (long long)with.chords, without.hit ? "hit" : "MISSED",
                    without.hit ? length(without.p - exact) : 0.0);
        // The crossing chord stands ≤ tolerance below the arc: it crosses within
        // √(2Rε) − √(2R(ε − tol)) of the path, plus the float plane intersection's error
        // (~1e−8 m in height over the grazing angle √(2ε/R) ≥ 3e−4).
        const double bound = std::sqrt(2 * R * eps) - std::sqrt(2 * R * (eps - 1e-9)) +
                             1e-8 / std::sqrt(2 * eps / R) * 3;
        EXPECT_LT(eWith, bound) << "graze " << eps << " m deep";
    }
    EXPECT_GT(missedWithout, 0) << "the long chords should have missed the shallowest grazes";
    // Just above the apex: the path does not touch it, and neither does the walk.
    EXPECT_FALSE(walkToPlane(k, o, d, yApex + 1e-6, true, 0.1).hit);
}

}  // namespace
}  // namespace mirage
