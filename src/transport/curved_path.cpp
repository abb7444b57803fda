// Fermat paths by Dormand–Prince RK5(4)7M and forward Euler (curved_path.h says what and why).
#include "transport/curved_path.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mirage {

namespace {

// The integrated state y = (r, v, O): 7 numbers.
using State = std::array<double, 7>;

State pack(const PathState& s) {
    return {s.r.x, s.r.y, s.r.z, s.v.x, s.v.y, s.v.z, s.opl};
}

PathState unpack(const State& y, double arc) {
    PathState s;
    s.r = Vec3d(y[0], y[1], y[2]);
    s.v = Vec3d(y[3], y[4], y[5]);
    s.opl = y[6];
    s.arc = arc;
    return s;
}

// Right-hand side f(y) = (v/n, ∇n, n) of eq. 9–11, counting field evaluations.
struct Rhs {
    const IndexField& field;
    double lambda;
    int64_t* evaluations;
    State operator()(const State& y) const {
        double n;
        Vec3d g;
        field.eval(Vec3d(y[0], y[1], y[2]), lambda, &n, &g);
        ++*evaluations;
        const double inv = 1.0 / n;
        return {y[3] * inv, y[4] * inv, y[5] * inv, g.x, g.y, g.z, n};
    }
};

// Dormand–Prince RK5(4)7M (Dormand & Prince 1980, table 2; Hairer et al. table II.5.2).
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                 a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                 a64 = 49.0 / 176, a65 = -5103.0 / 18656;
// Fifth-order weights (also the 7th stage's row: first same as last).
constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784,
                 b6 = 11.0 / 84;
// Fifth minus fourth order weights: the local error estimate.
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920,
                 e5 = -17253.0 / 339200, e6 = 22.0 / 525, e7 = -1.0 / 40;
static_assert(c2 > 0 && c3 > c2 && c4 > c3 && c5 > c4, "stage nodes increase");

template <typename F>
State combine(const State& y, F&& term) {
    State out;
    for (int i = 0; i < 7; ++i) out[i] = y[i] + term(i);
    return out;
}

// The step the caller allows from state s: remaining length, maxStep, the step cap callback.
double allowedStep(const PathState& s, double remaining, const CurvedPathSettings& set) {
    double h = std::min(remaining, set.maxStep);
    if (set.stepCap) {
        const double cap = set.stepCap(s.r, s.direction());
        if (cap > 0) h = std::min(h, cap);
    }
    return h;
}

// One Dormand–Prince trial step of length h from y (k1 = f(y)): the fifth-order solution, the
// last stage f(yNew) (the next step's k1: first same as last) and the error estimate, as a
// multiple of the tolerance.
struct TrialStep {
    State yNew, k7;
    double err;
};
TrialStep dormandPrince(const Rhs& f, const State& y, const State& k1, double h, double tol) {
    const State k2 = f(combine(y, [&](int i) { return h * a21 * k1[i]; }));
    const State k3 = f(combine(y, [&](int i) { return h * (a31 * k1[i] + a32 * k2[i]); }));
    const State k4 =
        f(combine(y, [&](int i) { return h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]); }));
    const State k5 = f(combine(
        y, [&](int i) { return h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]); }));
    const State k6 = f(combine(y, [&](int i) {
        return h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    }));
    TrialStep t;
    t.yNew = combine(y, [&](int i) {
        return h * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
    });
    t.k7 = f(t.yNew);
    double err = 0;
    for (int i = 0; i < 7; ++i) {
        const double e =
            h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * t.k7[i]);
        err = std::max(err, std::abs(e));
    }
    t.err = err / tol;
    return t;
}

// The stepper along one path: its state, its memory between steps (FSAL's k1, the step the
// controller proposes, whether the last trial was rejected) and the figures of the result.
class PathStepper {
public:
    PathStepper(const IndexField& field, const Vec3d& origin, const Vec3d& direction,
                double lambdaNm, double arcLength, const CurvedPathSettings& set,
                const ChordVisitor& visit)
        : mF{field, lambdaNm, &mRes.evaluations},
          mField(field),
          mArcLength(arcLength),
          mSet(set),
          mVisit(visit),
          // Stop a little short of L only by rounding: a remaining length below this ends the
          // path.
          mEndSlack(1e-12 * std::max(1.0, arcLength)) {
        mS.r = origin;
        double n0;
        Vec3d g0;
        field.eval(origin, lambdaNm, &n0, &g0);
        ++mRes.evaluations;
        mS.v = normalize(direction) * n0;
        mY = pack(mS);
        // First trial step: a fraction of the length scale n/|∇n| (the radius of curvature of a
        // path is at least that), shrunk as tol^(1/5) as the controller would.
        const double g0len = length(g0);
        mHNext = g0len > 0 ? 0.1 * n0 / g0len * std::pow(set.tolerance, 0.2) : set.maxStep;
    }

    CurvedPathResult run() {
        while (mArcLength - mS.arc > mEndSlack && !mRes.stopped) {
            if (mRes.steps + mRes.rejected >= mSet.maxSteps) {
                mRes.capped = true;
                break;
            }
            if (straightChord()) continue;
            if (mSet.method == PathMethod::Euler) {
                eulerStep();
                continue;
            }
            if (!rk45Step()) break;
        }
        mRes.end = mS;
        return mRes;
    }

private:
    // An accepted step to yNew over arc h: the chord from the state before to the one after
    // goes to the visitor.
    void accept(const State& yNew, double h, bool straight) {
        const PathState from = unpack(mY, mS.arc);
        mY = yNew;
        mS = unpack(mY, mS.arc + h);
        ++mRes.steps;
        if (straight) ++mRes.straightChords;
        if (mVisit && !mVisit(from, mS, straight)) mRes.stopped = true;
    }

    // Constant n ahead: one exact straight chord (v and n unchanged, O grows by n·d). False
    // when the field promises no straight stretch here.
    bool straightChord() {
        const double remaining = mArcLength - mS.arc;
        const Vec3d dir = mS.direction();
        const double straight = mField.straightDistance(mS.r, dir, remaining);
        if (!(straight > 0)) return false;
        const double d = std::min(straight, remaining);
        const double n = length(mS.v);
        State yNew = mY;
        yNew[0] += d * dir.x;
        yNew[1] += d * dir.y;
        yNew[2] += d * dir.z;
        yNew[6] += n * d;
        accept(yNew, d, true);
        mHaveK1 = false;
        return true;
    }

    // Forward Euler, the fixed step eulerStep (figure 1 of Gutierrez et al. 2005).
    void eulerStep() {
        const double h = std::min(mSet.eulerStep, allowedStep(mS, mArcLength - mS.arc, mSet));
        const State k = mF(mY);
        accept(combine(mY, [&](int i) { return h * k[i]; }), h, false);
    }

    // One Dormand–Prince trial step, accepted or rejected by its error estimate, and the
    // controller's next step. False when the field gave no finite answer even at the shortest
    // step: the path ends there, capped.
    bool rk45Step() {
        const double h = std::min(mHNext, allowedStep(mS, mArcLength - mS.arc, mSet));
        const bool clipped = h < mHNext;  // limited by the caller, not by the controller
        if (!mHaveK1) {
            mK1 = mF(mY);
            mHaveK1 = true;
        }
        const TrialStep t = dormandPrince(mF, mY, mK1, h, mSet.tolerance);
        // The controller's next proposal, from the error of this trial (exponent 1/5: the
        // error estimate is that of the fourth-order solution).
        const double factor = !std::isfinite(t.err) ? mSet.maxShrink
                              : t.err > 0           ? mSet.safety * std::pow(t.err, -0.2)
                                                    : mSet.maxGrowth;
        const double grow = mLastRejected ? 1.0 : mSet.maxGrowth;
        const double proposal = h * std::clamp(factor, mSet.maxShrink, grow);

        if (!std::isfinite(t.err) && h <= mSet.minStep) {
            mRes.capped = true;
            return false;
        }
        if (t.err <= 1.0 || h <= mSet.minStep) {
            if (t.err > 1.0) ++mRes.forcedSteps;
            accept(t.yNew, h, false);
            mK1 = t.k7;
            mLastRejected = false;
            // A step clipped by the caller says nothing about the step the error allows.
            mHNext = clipped ? std::max(mHNext, proposal) : proposal;
        } else {
            ++mRes.rejected;
            mLastRejected = true;
            mHNext = std::max(proposal, mSet.minStep);
        }
        return true;
    }

    CurvedPathResult mRes;
    const Rhs mF;
    const IndexField& mField;
    const double mArcLength;
    const CurvedPathSettings& mSet;
    const ChordVisitor& mVisit;
    const double mEndSlack;
    PathState mS;
    State mY, mK1{};
    bool mHaveK1 = false;  // FSAL: k1 of the next step is k7 of the accepted one
    double mHNext;
    bool mLastRejected = false;
};

}  // namespace

CurvedPathResult traceCurvedPath(const IndexField& field, const Vec3d& origin,
                                 const Vec3d& direction, double lambdaNm, double arcLength,
                                 const CurvedPathSettings& set, const ChordVisitor& visit) {
    return PathStepper(field, origin, direction, lambdaNm, arcLength, set, visit).run();
}

}  // namespace mirage
