// The Fermat path stepper (transport/curved_path.h) against the exact path in the linear profile
// n = n0 + k·y (medium/linear_profile_path.h): end-point error under a tolerance-scaled bound
// for k across [−0.1, 0.1], the optical path length, the catenary n = C cosh(k(x − x0)/C), first
// order of forward Euler, FSAL's evaluation count, the step caps and straight chords.
#include <gtest/gtest.h>

#include <cmath>

#include "medium/index_field.h"
#include "medium/linear_profile_path.h"
#include "transport/curved_path.h"

namespace mirage {
namespace {

const Vec3d kYAxis(0, 1, 0);

TEST(LinearProfilePath, StraightWhenKIsZeroAndConsistentForSmallK) {
    const Vec3d o(1, 2, 3), d = normalize(Vec3d(1, -0.4, 0.3));
    const LinearProfilePath s = exactLinearProfilePath(1.3, 0.0, kYAxis, o, d, 7.0);
    EXPECT_NEAR(length(s.endPoint - (o + d * 7.0)), 0.0, 1e-14);
    EXPECT_NEAR(s.opticalPathLength, (1.3 + 2 * 0.0) * 7.0, 1e-13);
    // k → 0 is continuous: the k = 1e−9 path is within O(k·L²) of the straight one.
    const LinearProfilePath t = exactLinearProfilePath(1.3, 1e-9, kYAxis, o, d, 7.0);
    EXPECT_LT(length(t.endPoint - s.endPoint), 1e-7);
    EXPECT_NEAR(length(t.endDirection), 1.0, 1e-15);
}

TEST(CurvedPath, Rk45EndPointWithinToleranceScaledBoundAcrossK) {
    const double L = 10.0;
    const Vec3d o(0, 0.5, 0);
    for (int ik = -4; ik <= 4; ++ik) {
        const double k = 0.025 * ik;  // −0.1 … 0.1
        const LinearIndexField field(1.0, k);
        for (const Vec3d& dRaw : {Vec3d(1, 0.3, 0.2), Vec3d(1, -0.2, 0), Vec3d(0.2, 1, -0.1)}) {
            const Vec3d d = normalize(dRaw);
            const LinearProfilePath ex = exactLinearProfilePath(1.0, k, kYAxis, o, d, L);
            for (double tol : {1e-3, 1e-6, 1e-9, 1e-12}) {
                CurvedPathSettings set;
                set.tolerance = tol;
                const CurvedPathResult r = traceCurvedPath(field, o, d, 550, L, set);
                ASSERT_FALSE(r.capped);
                EXPECT_NEAR(r.end.arc, L, 1e-12);
                // Local errors ≤ tol per step add up (at most) over the path: bound tol·L, with
                // a factor 10 for the estimate being that of the 4th-order companion.
                const double bound = 10 * tol * L + 1e-13;
                EXPECT_LT(length(r.end.r - ex.endPoint), bound) << "k " << k << " tol " << tol;
                EXPECT_NEAR(r.end.opl, ex.opticalPathLength, bound) << "k " << k;
                EXPECT_LT(length(r.end.direction() - ex.endDirection), bound + 10 * tol);
            }
        }
    }
}

TEST(CurvedPath, EndPointLiesOnTheCatenary) {
    // In the x–y plane: n(y(x)) = C cosh(k (x − x0)/C), C = n·cos(angle to x) conserved.
    const double n0 = 1.0, k = -0.08, L = 12.0;
    const Vec3d o(0, 1, 0), d = normalize(Vec3d(1, 0.5, 0));
    const LinearIndexField field(n0, k);
    CurvedPathSettings set;
    set.tolerance = 1e-11;
    const CurvedPathResult r = traceCurvedPath(field, o, d, 550, L, set);
    const double nS = n0 + k * o.y, C = nS * d.x, u0 = nS * d.y;
    const double x0 = o.x - C / k * std::asinh(u0 / C);
    const double nEnd = n0 + k * r.end.r.y;
    EXPECT_NEAR(nEnd, C * std::cosh(k * (r.end.r.x - x0) / C), 1e-9);
    EXPECT_NEAR(r.end.v.x, C, 1e-12);  // ∂n/∂x = 0: the x component of v is a constant
    EXPECT_NEAR(r.end.r.z, 0.0, 1e-15);
    // The path turned: it rose and came back below its start (k < 0 bends it downwards).
    EXPECT_LT(r.end.direction().y, 0.0);
}

TEST(CurvedPath, EulerConvergesToFirstOrder) {
    const LinearIndexField field(1.0, 0.1);
    const Vec3d o(0, 0, 0), d = normalize(Vec3d(1, 0.2, 0));
    const LinearProfilePath ex = exactLinearProfilePath(1.0, 0.1, kYAxis, o, d, 5.0);
    double previous = 0;
    for (double h : {1e-2, 5e-3, 2.5e-3}) {
        CurvedPathSettings set;
        set.method = PathMethod::Euler;
        set.eulerStep = h;
        const CurvedPathResult r = traceCurvedPath(field, o, d, 550, 5.0, set);
        EXPECT_EQ(r.evaluations, r.steps + 1);
        const double err = length(r.end.r - ex.endPoint);
        if (previous > 0) {
            EXPECT_NEAR(previous / err, 2.0, 0.1) << "h " << h;
        }
        previous = err;
    }
}

TEST(CurvedPath, FsalCountsSixEvaluationsPerTrialStep) {
    const LinearIndexField field(1.2, -0.05);
    CurvedPathSettings set;
    set.tolerance = 1e-10;
    const CurvedPathResult r =
        traceCurvedPath(field, Vec3d(0, 0, 0), normalize(Vec3d(1, 1, 0)), 550, 8.0, set);
    EXPECT_GT(r.steps, 5);
    // One evaluation at the origin, k1 once, then k2…k7 per trial (k7 is the next k1).
    EXPECT_EQ(r.evaluations, 2 + 6 * (r.steps + r.rejected));
}

TEST(CurvedPath, StepCapAndHardCapAndVisitorStop) {
    const LinearIndexField field(1.0, 0.05);
    const Vec3d o(0, 0, 0), d(1, 0, 0);
    CurvedPathSettings set;
    set.tolerance = 1e-4;
    set.stepCap = [](const Vec3d&, const Vec3d&) { return 0.01; };
    int64_t chords = 0;
    double longest = 0;
    CurvedPathResult r = traceCurvedPath(field, o, d, 550, 1.0, set,
                                         [&](const PathState& a, const PathState& b, bool) {
                                             ++chords;
                                             longest = std::max(longest, b.arc - a.arc);
                                             return true;
                                         });
    EXPECT_EQ(chords, r.steps);
    EXPECT_GE(r.steps, 100);
    EXPECT_LE(longest, 0.01 + 1e-15);

    set.stepCap = nullptr;
    set.maxStep = 0.1;
    set.maxSteps = 5;
    r = traceCurvedPath(field, o, d, 550, 1.0, set);
    EXPECT_TRUE(r.capped);
    EXPECT_NEAR(r.end.arc, 0.5, 1e-12);

    set.maxSteps = 1000;
    r = traceCurvedPath(field, o, d, 550, 1.0, set,
                        [](const PathState&, const PathState& b, bool) { return b.arc < 0.3; });
    EXPECT_TRUE(r.stopped);
    EXPECT_FALSE(r.capped);
    EXPECT_NEAR(r.end.arc, 0.3, 1e-9);
}

TEST(CurvedPath, ConstantIndexIsOneExactStraightChord) {
    const LinearIndexField field(1.33, 0.0);
    const Vec3d o(1, 2, 3), d = normalize(Vec3d(-1, 2, 0.5));
    const CurvedPathResult r = traceCurvedPath(field, o, d, 550, 40.0, CurvedPathSettings());
    EXPECT_EQ(r.steps, 1);
    EXPECT_EQ(r.straightChords, 1);
    EXPECT_EQ(r.evaluations, 1);
    EXPECT_NEAR(length(r.end.r - (o + d * 40.0)), 0.0, 1e-13);
    EXPECT_NEAR(r.end.opl, 1.33 * 40.0, 1e-12);
}

}  // namespace
}  // namespace mirage
