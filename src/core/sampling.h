// Sampling warps: maps from uniform numbers in [0, 1)² to directions with a known density.
// Each consumes exactly two numbers, u1 then u2, in the order of its arguments. Callers that draw
// them from a Sampler name them first (float u1 = s.get1D(), u2 = s.get1D()) wherever the order
// matters, since the order in which a function's arguments are evaluated is unspecified.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace mirage {

// The unit vector at polar angle θ (given by its sine and cosine) and azimuth φ about +z.
inline Vec3 sphericalDirection(float sinTheta, float cosTheta, float phi) {
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

// Uniform direction on the sphere, pdf 1/4π: z = cos θ is uniform on [−1, 1] (Archimedes'
// hat-box theorem), φ uniform on [0, 2π).
inline Vec3 sampleUniformSphere(float u1, float u2) {
    float z = 1.f - 2.f * u1;
    float r = safeSqrt(1.f - z * z);
    float phi = 2.f * kPi * u2;
    return sphericalDirection(r, z, phi);
}

// Uniform direction in the cone about `axis` (unit) with cos θ ≥ cosMax, pdf 1 / 2π(1 − cosMax):
// cos θ is uniform on [cosMax, 1] (the sphere's area is uniform in z).
inline Vec3 sampleUniformCone(const Vec3& axis, float cosMax, float u1, float u2) {
    const float cosT = 1.f - u1 * (1.f - cosMax), sinT = safeSqrt(1.f - cosT * cosT);
    const float phi = 2.f * kPi * u2;
    return Frame(axis).toWorld(sphericalDirection(sinT, cosT, phi));
}

// A direction about `axis` (unit) at an angle θ uniform on [0, θmax] (0 < θmax ≤ π), its
// azimuth uniform: density 1 / (2π θmax sin θ) within θmax (the solid angle between θ and θ + dθ
// is 2π sin θ dθ). It grows as 1/θ towards the axis, where every smooth density stays finite: a
// ray drawn so passes within a distance D of a point on the axis with a probability ∝ D, not D²
// (render/light_lobes.h: the lamps' lobes).
inline Vec3 sampleUniformAngle(const Vec3& axis, float thetaMax, float u1, float u2) {
    const float theta = u1 * thetaMax;
    return Frame(axis).toWorld(
        sphericalDirection(std::sin(theta), std::cos(theta), 2.f * kPi * u2));
}

// sampleUniformAngle's density of the unit direction w (1/sr): sin θ is |axis × w|, exact near
// the axis where an arccosine of the dot product loses it.
inline float uniformAnglePdf(const Vec3& axis, float thetaMax, const Vec3& w) {
    const float sinT = length(cross(axis, w)), theta = std::atan2(sinT, dot(axis, w));
    if (!(theta <= thetaMax)) return 0.f;
    return 1.f / (2.f * kPi * thetaMax * std::max(sinT, 1e-12f));
}

// Cosine-weighted hemisphere about +z, pdf cos θ / π (Malley's method: a uniform point on the
// unit disc lifted to the hemisphere), with the concentric disc mapping of Shirley & Chiu
// (1997), which keeps neighbouring (u1, u2) neighbouring on the disc.
inline Vec3 sampleCosineHemisphere(float u1, float u2) {
    float a = 2.f * u1 - 1.f, b = 2.f * u2 - 1.f;
    if (a == 0.f && b == 0.f) return {0.f, 0.f, 1.f};
    float r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = 0.25f * kPi * (b / a);
    } else {
        r = b;
        phi = 0.5f * kPi - 0.25f * kPi * (a / b);
    }
    float x = r * std::cos(phi), y = r * std::sin(phi);
    return {x, y, safeSqrt(1.f - x * x - y * y)};
}

// The same density with the polar disc mapping: radius √u1, azimuth 2π u2, so cos θ = √(1 − u1).
// It maps (u1, u2) to other directions than sampleCosineHemisphere, so each caller keeps the
// form its random numbers have always met.
inline Vec3 sampleCosineHemispherePolar(float u1, float u2) {
    float r = std::sqrt(u1), phi = 2.f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), safeSqrt(1.f - u1)};
}

}  // namespace mirage
