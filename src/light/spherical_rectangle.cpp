#include "light/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace mirage {

namespace {

// Double precision throughout: Ω is a small difference of angles near 2π for a distant light.
struct D3 {
    double x, y, z;
};
double dot3(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 unitCross(const D3& a, const D3& b) {
    const D3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    const double l = std::sqrt(dot3(c, c));
    return {c.x / l, c.y / l, c.z / l};
}
// The interior angle of the spherical rectangle between two adjacent edge planes.
double angleBetween(const D3& na, const D3& nb) {
    return std::acos(std::clamp(-dot3(na, nb), -1.0, 1.0));
}

}  // namespace

bool SphericalRectangle::setup(const Vec3& o, const Vec3& s, const Vec3& ex, const Vec3& ey) {
    const float exl = length(ex), eyl = length(ey);
    if (!(exl > 0.f && eyl > 0.f)) return false;
    mX = ex / exl;
    mY = ey / eyl;
    if (std::abs(dot(mX, mY)) > 1e-4f) return false;
    mO = o;
    mZ = cross(mX, mY);
    const Vec3 d = s - o;
    mZ0 = dot(d, mZ);
    if (mZ0 > 0.0) {  // the frame's z points away from the rectangle
        mZ = -mZ;
        mZ0 = -mZ0;
    }
    if (!(mZ0 < 0.0)) return false;
    mX0 = dot(d, mX);
    mY0 = dot(d, mY);
    mX1 = mX0 + exl;
    mY1 = mY0 + eyl;
    // The four corners seen from o, and the normals of the planes through o and each edge.
    const D3 v00{mX0, mY0, mZ0}, v01{mX0, mY1, mZ0}, v10{mX1, mY0, mZ0}, v11{mX1, mY1, mZ0};
    const D3 n0 = unitCross(v00, v10), n1 = unitCross(v10, v11), n2 = unitCross(v11, v01),
             n3 = unitCross(v01, v00);
    const double g0 = angleBetween(n0, n1), g1 = angleBetween(n1, n2), g2 = angleBetween(n2, n3),
                 g3 = angleBetween(n3, n0);
    // Ω = Σ interior angles − 2π (Girard), split as the paper does for the inversion below.
    mB0 = n0.z;
    mB1 = n2.z;
    mK = 2.0 * kPi - g2 - g3;
    mS = g0 + g1 - mK;
    return mS > 0.0 && std::isfinite(mS);
}

Vec3 SphericalRectangle::sample(double u1, double u2) const {
    // u1 picks the solid angle left of a plane through o and the y axis: its x position xu.
    const double au = u1 * mS + mK;
    const double sinAu = std::sin(au);
    const double fu = std::abs(sinAu) > 1e-12 ? (std::cos(au) * mB0 - mB1) / sinAu : 1e12;
    double cu = std::copysign(1.0 / std::sqrt(fu * fu + mB0 * mB0), fu);
    cu = std::clamp(cu, -1.0, 1.0);
    const double sinCu = std::sqrt(std::max(1.0 - cu * cu, 0.0));
    const double xu =
        sinCu > 0.0 ? std::clamp(-(cu * mZ0) / sinCu, mX0, mX1) : (cu > 0.0 ? mX1 : mX0);
    // u2 is uniform in the cosine of the elevation along that line (its y position yv).
    const double dist = std::sqrt(xu * xu + mZ0 * mZ0);
    const double h0 = mY0 / std::sqrt(dist * dist + mY0 * mY0);
    const double h1 = mY1 / std::sqrt(dist * dist + mY1 * mY1);
    const double hv = h0 + u2 * (h1 - h0), hv2 = hv * hv;
    const double yv =
        hv2 < 1.0 - 1e-9 ? std::clamp(hv * dist / std::sqrt(1.0 - hv2), mY0, mY1) : mY1;
    return mO + mX * float(xu) + mY * float(yv) + mZ * float(mZ0);
}

}  // namespace mirage
