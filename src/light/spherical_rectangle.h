// Sampling a rectangle uniformly in the solid angle it subtends from a point (Ureña, Fajardo &
// King 2013, "An Area-Preserving Parametrization for Spherical Rectangles", EGSR). A quad light
// sampled uniformly over its area weights each sample by cosθ_l A / d², which has no bound
// near the light: in a medium, scattering points millimetres from the emitter (a light just
// under the ceiling of a water-filled box) give rare, huge next-event estimates, coloured
// speckles that more samples only thin out (the variance of that estimator over the volume is
// infinite). Sampled in solid angle, a constant-radiance emitter's estimate is L Ω: bounded by
// 2π L wherever the point is. Unbiased either way; only the variance changes.
#pragma once

#include "core/math.h"

namespace mirage {

// The spherical rectangle a rectangle (corner s, orthogonal edges ex, ey) subtends from o.
class SphericalRectangle {
public:
    // False when o lies in the rectangle's plane (it subtends nothing) or the edges are not
    // orthogonal (not a rectangle: the caller samples the area instead).
    bool setup(const Vec3& o, const Vec3& s, const Vec3& ex, const Vec3& ey);
    // Solid angle Ω (sr); the sample's pdf in solid angle is 1/Ω.
    double solidAngle() const { return mS; }
    // The point on the rectangle for (u1, u2) in [0, 1)², uniform in solid angle.
    Vec3 sample(double u1, double u2) const;

private:
    Vec3 mO, mX, mY, mZ;             // local frame at o: x, y along the edges, z away from it
    double mX0, mX1, mY0, mY1, mZ0;  // the rectangle in that frame (z0 ≤ 0)
    double mB0, mB1, mK, mS;         // the paper's b0, b1, k and Ω
};

}  // namespace mirage
