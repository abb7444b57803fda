// The exact light path in the linear profile n = n0 + k·(x·a) (LinearIndexField): the known
// answer that the path stepper is tested and benchmarked against.
//
// With v = n dr/dl (Gutierrez et al. 2005, eq. 9–11), dv/dl = ∇n = k·a is constant, so
// v(l) = v0 + k·l·a: the component w of v across the axis is conserved (C = |w| = n·cos of the
// angle to the plane across a; Snell's invariant) and u = v·a grows linearly, u(l) = u0 + k·l.
// Since |dr/dl| = 1, n(l) = |v(l)| = sqrt(C² + u²), and integrating dr/dl = v/n gives
//   (r − r0)·a = (n(l) − n(0)) / k = l (u + u0) / (n + n(0)),
//   r⊥ − r0⊥  = w · I,   I = ∫ dl/n = (asinh(u/C) − asinh(u0/C)) / k,
//   OPL = ∫ n dl = ½ [l·n + u0·l (u + u0)/(n + n(0))] + ½ C²·I.
// Eliminating l: n = C cosh(k (s − s0)/C) along the distance s across the axis — the catenary.
// Every expression is arranged so that k → 0 loses no digits (no division of
// nearly equal differences by k), and evaluated in long double.
#pragma once

#include <cmath>

#include "core/math.h"

namespace mirage {

struct LinearProfilePath {
    Vec3d endPoint, endDirection;   // endDirection unit
    double opticalPathLength = 0;   // ∫ n dl, metres
};

inline LinearProfilePath exactLinearProfilePath(double n0, double k, const Vec3d& axis,
                                                const Vec3d& origin, const Vec3d& direction,
                                                double length) {
    using L = long double;
    const Vec3d a = normalize(axis), d = normalize(direction);
    const L nStart = L(n0) + L(k) * L(dot(origin, a));
    const L u0 = nStart * L(dot(d, a));
    const L w[3] = {nStart * (L(d.x) - L(dot(d, a)) * L(a.x)),
                    nStart * (L(d.y) - L(dot(d, a)) * L(a.y)),
                    nStart * (L(d.z) - L(dot(d, a)) * L(a.z))};
    const L C = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    const L l = length, u = u0 + L(k) * l;
    const L n = std::sqrt(C * C + u * u);

    // I = ∫ dl / n. asinh(p) − asinh(q) = asinh(p·sqrt(1+q²) − q·sqrt(1+p²)); when p and q share
    // a sign the difference is rewritten as (p² − q²)/(…) with p − q = k·l/C, so k cancels.
    L I = 0;
    if (k == 0.0) {
        I = l / n;
    } else if (C > 0) {
        const L p = u / C, q = u0 / C;
        const L sp = std::sqrt(1 + p * p), sq = std::sqrt(1 + q * q);
        if (p * q > 0) {
            const L sOverK = (l / C) * (p + q) / (p * sq + q * sp);
            const L s = sOverK * L(k);
            const L asinhc = std::abs(s) < 1e-12L ? 1 - s * s / 6 : std::asinh(s) / s;
            I = sOverK * asinhc;
        } else {
            I = std::asinh(p * sq - q * sp) / L(k);
        }
    }
    const L along = l * (u + u0) / (n + nStart);
    const L opl = 0.5L * (l * n + u0 * l * (u + u0) / (n + nStart)) + 0.5L * C * C * I;

    LinearProfilePath r;
    r.endPoint = Vec3d(double(L(origin.x) + along * L(a.x) + w[0] * I),
                       double(L(origin.y) + along * L(a.y) + w[1] * I),
                       double(L(origin.z) + along * L(a.z) + w[2] * I));
    r.endDirection = Vec3d(double((u * L(a.x) + w[0]) / n), double((u * L(a.y) + w[1]) / n),
                           double((u * L(a.z) + w[2]) / n));
    r.opticalPathLength = double(opl);
    return r;
}

}  // namespace mirage
