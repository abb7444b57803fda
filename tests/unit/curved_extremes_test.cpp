// The curved-path cells of the extremes matrix: the path stepper (transport/
// curved_path.h) at the ends of its knobs and fields, against the exact path in the linear
// profile n = n0 + k·y (medium/linear_profile_path.h, a catenary in the ray's plane).
//   - tolerance 1e−3 and 1e−14: the end point within the tolerance of the exact one (1e−14 is
//     below double rounding on 10 m: there the bound is rounding's, 1e−13 m), steps bounded;
//   - |∇n| tiny (k = 1e−12/m): the straight line to 1e−9 m, in one step;
//   - |∇n| extreme (k = ±1e3/m: a radius of curvature n/|∇n| of a millimetre): finite, bounded
//     steps, on the exact path, or reported capped; a field whose n reaches 0 on the path ends
//     finite and bounded;
//   - a path tangent to a plane (at its apex): no NaN, hit or miss as the exact path says
//     whenever the plane is farther from the apex than a chord's sagitta.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "medium/index_field.h"
#include "medium/linear_profile_path.h"
#include "transport/curved_path.h"
#include "transport/curved_tracking.h"

namespace mirage {
namespace {

const Vec3d kYAxis(0, 1, 0);

bool finiteState(const PathState& s) {
    return std::isfinite(s.r.x) && std::isfinite(s.r.y) && std::isfinite(s.r.z) &&
           std::isfinite(s.v.x) && std::isfinite(s.v.y) && std::isfinite(s.v.z) &&
           std::isfinite(s.opl) && std::isfinite(s.arc);
}

struct Worst {
    double error = 0;
    int64_t trials = 0;  // accepted + rejected steps, most of any path
};

// The worst end-point error against the exact path over k ∈ ±{0.01, 0.05, 0.1} and three start
// directions, 10 m each (the paths of the tolerance table in docs/curved-light.md).
Worst worstOverProfiles(double tolerance) {
    Worst w;
    const Vec3d o(0, 0.5, 0);
    for (double k : {-0.1, -0.05, -0.01, 0.01, 0.05, 0.1}) {
        const LinearIndexField field(1.0, k);
        for (const Vec3d& dRaw : {Vec3d(1, 0.3, 0.2), Vec3d(1, -0.2, 0), Vec3d(0.2, 1, -0.1)}) {
            const Vec3d d = normalize(dRaw);
            CurvedPathSettings set;
            set.tolerance = tolerance;
            const CurvedPathResult r = traceCurvedPath(field, o, d, 550, 10.0, set);
            EXPECT_FALSE(r.capped) << "k " << k;
            EXPECT_TRUE(finiteState(r.end)) << "k " << k;
            EXPECT_NEAR(r.end.arc, 10.0, 1e-11);
            const LinearProfilePath ex = exactLinearProfilePath(1.0, k, kYAxis, o, d, 10.0);
            w.error = std::max(w.error, length(r.end.r - ex.endPoint));
            w.trials = std::max(w.trials, r.steps + r.rejected);
        }
    }
    return w;
}

TEST(CurvedExtremes, LoosestToleranceStaysWithinIt) {
    const Worst w = worstOverProfiles(1e-3);
    std::printf("tolerance 1e-3: worst end-point error %.3g m, most trial steps %lld\n", w.error,
                (long long)w.trials);
    // 1.0e−3 m measured: per-step errors ≤ tolerance, summed over a handful of steps.
    EXPECT_LT(w.error, 2e-3);
    EXPECT_LT(w.trials, 20);  // a handful of long steps: 10 m at R ≥ 10 m
}

TEST(CurvedExtremes, TightestToleranceReachesRounding) {
    const Worst w = worstOverProfiles(1e-14);
    std::printf("tolerance 1e-14: worst end-point error %.3g m, most trial steps %lld\n",
                w.error, (long long)w.trials);
    // ~1.6e−14 m measured: a few ulps of 10 m (1.8e−15 m each) summed over the steps.
    EXPECT_LT(w.error, 1e-13);
    EXPECT_LT(w.trials, 1000);  // far below the default cap of 1e7
}

TEST(CurvedExtremes, TinyGradientIsTheStraightLine) {
    // k = 1e−12/m bends a 10 m path by k·L²/2 = 5e−11 m.
    const LinearIndexField field(1.0, 1e-12);
    const Vec3d o(0.3, -2, 1), d = normalize(Vec3d(1, 0.1, -0.4));
    for (double tol : {1e-3, 1e-6, 1e-12}) {
        CurvedPathSettings set;
        set.tolerance = tol;
        const CurvedPathResult r = traceCurvedPath(field, o, d, 550, 10.0, set);
        ASSERT_TRUE(finiteState(r.end));
        EXPECT_FALSE(r.capped);
        EXPECT_LT(length(r.end.r - (o + d * 10.0)), 1e-9) << tol;
        const LinearProfilePath ex = exactLinearProfilePath(1.0, 1e-12, kYAxis, o, d, 10.0);
        EXPECT_LT(length(r.end.r - ex.endPoint), 1e-12) << tol;
        EXPECT_LE(r.steps, 2) << "its radius of curvature is 1e12 m";
    }
}

TEST(CurvedExtremes, MillimetreRadiusOfCurvatureIsFollowedOrReportedCapped) {
    // n = 1 ± 1e3·y: at y = 0 the radius of curvature n/|∇n| is 1 mm. Horizontal into k > 0 the
    // path turns up within millimetres and climbs to n ≈ 1e3; 45° up into k < 0 it turns back
    // 0.29 mm up (n = C = cos 45°) and dives to n ≈ 1e3.
    struct Case {
        double k;
        Vec3d d;
    };
    for (const Case& c : {Case{1e3, Vec3d(1, 0, 0)}, Case{-1e3, normalize(Vec3d(1, 1, 0))}}) {
        const LinearIndexField field(1.0, c.k);
        const Vec3d o(0, 0, 0);
        CurvedPathSettings set;
        set.tolerance = 1e-9;
        const CurvedPathResult r = traceCurvedPath(field, o, c.d, 550, 1.0, set);
        ASSERT_TRUE(finiteState(r.end)) << c.k;
        EXPECT_FALSE(r.capped) << c.k;
        EXPECT_NEAR(r.end.arc, 1.0, 1e-12);
        const LinearProfilePath ex = exactLinearProfilePath(1.0, c.k, kYAxis, o, c.d, 1.0);
        const double err = length(r.end.r - ex.endPoint);
        std::printf("k %g: %lld steps, %lld rejected, end-point error %.3g m\n", c.k,
                    (long long)r.steps, (long long)r.rejected, err);
        EXPECT_LT(err, 1e-6) << c.k;
        EXPECT_LT(r.steps + r.rejected, 2000) << c.k;

        // The same path under a cap of 20 steps: reported, finite, no further.
        set.maxSteps = 20;
        const CurvedPathResult capped = traceCurvedPath(field, o, c.d, 550, 1.0, set);
        EXPECT_TRUE(capped.capped) << c.k;
        EXPECT_EQ(capped.steps + capped.rejected, 20) << c.k;
        EXPECT_TRUE(finiteState(capped.end)) << c.k;
        EXPECT_LT(capped.end.arc, 1.0);
    }
}

TEST(CurvedExtremes, IndexReachingZeroEndsFiniteAndBounded) {
    // Straight up into n = 1 − 1e3·y: n = 0 at y = 1 mm, where v/n has no limit the stepper can
    // follow. Whatever it does there, it must end finite, within its cap.
    const LinearIndexField field(1.0, -1e3);
    CurvedPathSettings set;
    set.maxSteps = 100000;
    const CurvedPathResult r = traceCurvedPath(field, Vec3d(0, 0, 0), kYAxis, 550, 1.0, set);
    std::printf("n → 0: capped %d, arc %.3g m, %lld steps, %lld rejected, %lld forced\n",
                int(r.capped), r.end.arc, (long long)r.steps, (long long)r.rejected,
                (long long)r.forcedSteps);
    EXPECT_TRUE(finiteState(r.end));
    EXPECT_LE(r.steps + r.rejected, set.maxSteps);
    EXPECT_TRUE(r.capped || r.end.arc >= 1.0 - 1e-12);
}

// A path that rises at 0.1 rad in n = 1 − 0.05·y and bends back down: its apex lies at
// n = C = cos 0.1 (Snell's invariant), y = (1 − C)/0.05, radius of curvature C/0.05 ≈ 19.9 m.
struct Apex {
    double k = -0.05, theta = 0.1;
    Vec3d d = Vec3d(std::cos(0.1), std::sin(0.1), 0);
    double C = std::cos(0.1);
    double y = (1 - std::cos(0.1)) / 0.05;
    double radius = std::cos(0.1) / 0.05;
    // The arc length to where the exact path first reaches height yPlane (< y), by bisection.
    double arcTo(double yPlane) const {
        double lo = 0, hi = std::sin(theta) / -k;  // the apex: u = sin θ + k·l = 0
        for (int i = 0; i < 100; ++i) {
            const double mid = 0.5 * (lo + hi);
            const LinearProfilePath p = exactLinearProfilePath(1.0, k, kYAxis, Vec3d(0, 0, 0), d,
                                                               mid);
            (p.endPoint.y < yPlane ? lo : hi) = mid;
        }
        return lo;
    }
};

// The chord walk against the plane y = yPlane (chords from below or above alike).
CurvedWalkEnd walkToPlane(const Apex& a, double yPlane, const CurvedPathSettings& set) {
    const LinearIndexField field(1.0, a.k);
    const ChordSurfaceTest plane = [&](const Ray& chord, float tMax) {
        if (chord.d.y == 0.f) return kInfinity;
        const float t = (float(yPlane) - chord.o.y) / chord.d.y;
        return t > 0.f && t < tMax ? t : kInfinity;
    };
    return walkCurvedChords(CurvedWalk{field, set, 6.f, plane}, Ray{Vec3(0, 0, 0), Vec3(a.d)}, 550,
                            [](const CurvedChord&, CurvedWalkEnd*) { return true; });
}

TEST(CurvedExtremes, PathTangentToAPlaneHitsOrMissesAsTheExactPath) {
    const Apex a;
    CurvedPathSettings set;
    set.tolerance = 1e-9;
    set.maxStep = 0.1;
    // A 0.1 m chord stands at most h²/(8R) = 6.3e−5 m off the arc; planes farther than that from
    // the apex are told apart.
    const double sagitta = 0.1 * 0.1 / (8 * a.radius);
    for (double eps : {-4 * sagitta, -2 * sagitta, 2 * sagitta, 4 * sagitta}) {
        const CurvedWalkEnd end = walkToPlane(a, a.y + eps, set);
        ASSERT_TRUE(std::isfinite(end.p.x) && std::isfinite(end.p.y) && std::isfinite(end.arc));
        const bool hit = end.kind == CurvedWalkEnd::Kind::Surface;
        EXPECT_EQ(hit, eps < 0) << "plane " << eps << " m from the apex";
        if (hit) {
            // The arc stands above the plane by |ε| − s²/(2R) at a distance s from the apex;
            // the chord lies below the arc by at most the sagitta, so it crosses the plane
            // nearer the apex than the arc does, but not nearer than where the arc stands a
            // sagitta high: within √(2R|ε|) − √(2R(|ε| − sagitta)) of the exact crossing.
            const LinearProfilePath ex = exactLinearProfilePath(
                1.0, a.k, kYAxis, Vec3d(0, 0, 0), a.d, a.arcTo(a.y + eps));
            const double err = length(Vec3d(end.p) - ex.endPoint);
            const double e = std::abs(eps), bound = std::sqrt(2 * a.radius * e) -
                                                    std::sqrt(2 * a.radius * (e - sagitta)) +
                                                    1e-5;
            std::printf("plane %+.2e m from the apex: hit %.3g m from the exact crossing "
                        "(bound %.3g m)\n",
                        eps, err, bound);
            EXPECT_LT(err, bound);
        }
    }
    // Exactly tangent: either answer is right within the sagitta; none may be NaN, and a hit
    // lies near the apex (within the chord's half-length).
    const CurvedWalkEnd end = walkToPlane(a, a.y, set);
    ASSERT_TRUE(std::isfinite(end.p.x) && std::isfinite(end.p.y) && std::isfinite(end.arc));
    if (end.kind == CurvedWalkEnd::Kind::Surface) {
        EXPECT_NEAR(end.arc, std::sin(a.theta) / -a.k, 0.1);
    }
}

}  // namespace
}  // namespace mirage
