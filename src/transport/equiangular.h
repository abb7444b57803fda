// Distances along a ray drawn towards a point: equiangular sampling (Kulla & Fajardo 2012,
// "Importance Sampling Techniques for Path Tracing in Participating Media", §4.1).
//
// Light scattered once off a ray from a point light at c arrives as I T σs p / r², with
// r² = D² + (t − Δ)² (Δ: the parameter of the ray's point nearest c; D: its distance to c).
// Drawn ∝ T σs (delta tracking), a point next to the lamp scores 1/r² without bound: the
// fireflies of a lamp inside smoke. Drawn ∝ 1/r² over [a, b], the pdf
//     p(t) = D / ((θb − θa) (D² + (t − Δ)²)),  θ = atan((t − Δ)/D),
// cancels the inverse square: t = Δ + D tan(θa + u (θb − θa)) is uniform in the angle the
// segment subtends at c, and the estimate's variance stays bounded however close the ray
// passes. render/lamp_sampling.h combines it with delta tracking's own scattering points.
#pragma once

#include "core/math.h"

namespace mirage {

class EquiangularSegment {
public:
    EquiangularSegment() = default;  // empty
    // The segment [a, b] of the ray o + t d (d unit) seen from c. Empty when b ≤ a.
    EquiangularSegment(const Vec3& o, const Vec3& d, float a, float b, const Vec3& c);
    bool empty() const { return !(mThetaB > mThetaA); }
    float a() const { return mA; }
    float b() const { return mB; }
    // t in [a, b] from u in [0, 1), and its density (1/m).
    float sample(float u) const;
    float pdf(float t) const;

private:
    float mA = 0.f, mB = 0.f;      // the segment
    float mDelta = 0.f, mD = 1.f;  // the foot of the perpendicular from c, and its length (m)
    float mThetaA = 0.f, mThetaB = 0.f;
};

// A cone of directions from an apex: unit axis, half-angle acos(cosHalfAngle).
struct Cone {
    Vec3 apex, axis;
    float cosHalfAngle;
};

// The part of the segment [*t0, *t1] of the ray o + t d (d unit) inside the cone, replacing
// them: for a half-angle under 90° a convex set, and so one interval. False when the ray misses
// the cone within the segment. A half-angle of 90° or more (cosHalfAngle ≤ 0) keeps the whole
// segment, a superset of the part inside.
bool coneInterval(const Vec3& o, const Vec3& d, const Cone& cone, float* t0, float* t1);

}  // namespace mirage
