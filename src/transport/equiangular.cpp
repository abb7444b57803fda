#include "transport/equiangular.h"

#include <algorithm>
#include <cmath>

namespace mirage {

namespace {

// A ray passing through c (D = 0) has p(t) = δ-like at Δ: a floor on D keeps the angles finite;
// the floor's relative size keeps it invisible at the scales a scene has (1e-6 of the segment).
float footDistance(const Vec3& foot, const Vec3& c, float a, float b) {
    const float floor = 1e-6f * std::max({std::abs(a), std::abs(b), 1e-6f});
    return std::max(length(foot - c), floor);
}

}  // namespace

EquiangularSegment::EquiangularSegment(const Vec3& o, const Vec3& d, float a, float b,
                                       const Vec3& c)
    : mA(a), mB(b) {
    mDelta = dot(c - o, d);
    mD = footDistance(o + d * mDelta, c, a, b);
    if (!(b > a) || !std::isfinite(a) || !std::isfinite(b)) return;
    mThetaA = std::atan((a - mDelta) / mD);
    mThetaB = std::atan((b - mDelta) / mD);
}

float EquiangularSegment::sample(float u) const {
    const float theta = mThetaA + u * (mThetaB - mThetaA);
    return clamp(mDelta + mD * std::tan(theta), mA, mB);
}

float EquiangularSegment::pdf(float t) const {
    if (empty() || t < mA || t > mB) return 0.f;
    const float x = t - mDelta;
    return mD / ((mThetaB - mThetaA) * (mD * mD + x * x));
}

bool coneInterval(const Vec3& o, const Vec3& d, const Cone& cone, float* t0, float* t1) {
    const float a = *t0, b = *t1;
    if (!(b > a)) return false;
    // A half-angle of 90° or more is not convex: the whole segment, a superset of the lit part.
    const float cosCone = cone.cosHalfAngle;
    if (cosCone <= 0.f) return true;
    const Vec3& apex = cone.apex;
    const Vec3& axis = cone.axis;
    const Vec3 w = o - apex;
    auto inside = [&](float t) {
        const Vec3 v = w + d * t;
        return dot(v, axis) >= cosCone * length(v);
    };
    // The double cone's boundary: (v·axis)² = cos² |v|², v = w + t d, a quadratic in t whose
    // roots split [a, b] into pieces wholly inside or outside; the forward nappe being convex,
    // the inside pieces are contiguous.
    const float c2 = cosCone * cosCone, da = dot(d, axis), wa = dot(w, axis);
    const double A = double(da) * da - c2;
    const double B = 2.0 * (double(da) * wa - double(c2) * dot(d, w));
    const double C = double(wa) * wa - double(c2) * dot(w, w);
    float cuts[4] = {a, b, a, a};
    int n = 2;
    const double disc = B * B - 4.0 * A * C;
    if (std::abs(A) > 1e-12 && disc >= 0.0) {
        const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
        for (double r : {q / A, q != 0.0 ? C / q : double(a)})
            if (r > a && r < b) cuts[n++] = float(r);
    } else if (std::abs(A) <= 1e-12 && B != 0.0) {
        const double r = -C / B;
        if (r > a && r < b) cuts[n++] = float(r);
    }
    std::sort(cuts, cuts + n);
    bool any = false;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(cuts[i + 1] > cuts[i]) || !inside(0.5f * (cuts[i] + cuts[i + 1]))) continue;
        *t0 = any ? std::min(*t0, cuts[i]) : cuts[i];
        *t1 = any ? std::max(*t1, cuts[i + 1]) : cuts[i + 1];
        any = true;
    }
    return any;
}

}  // namespace mirage
