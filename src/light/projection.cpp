// Unions of cones and discs sampled as mixtures (projection.h).
#include "light/projection.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace mirage {

namespace {

// The entry of a cumulative sum that u ∈ [0, 1) of its total falls in.
size_t pickByCdf(const std::vector<double>& cdf, float u) {
    const double target = double(u) * cdf.back();
    const size_t i = size_t(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
    return std::min(i, cdf.size() - 1);
}

}  // namespace

void ConeUnion::add(const Vec3& axis, float cosMax) {
    const float c = clamp(cosMax, -1.f, 1.f);
    mCones.push_back(Cone{axis, c});
    mTotal += 2.0 * kPi * (1.0 - double(c));
    mCdf.push_back(mTotal);
}

size_t ConeUnion::pick(float u) const { return pickByCdf(mCdf, u); }

int ConeUnion::holding(const Vec3& w, size_t except) const {
    int n = 0;
    for (size_t k = 0; k < mCones.size(); ++k)
        n += k != except && dot(w, mCones[k].axis) >= mCones[k].cosMax;
    return n;
}

Vec3 ConeUnion::sample(float uPick, float u1, float u2, int* coverage) const {
    const size_t k = pick(uPick);
    const Vec3 w = sampleUniformCone(mCones[k].axis, mCones[k].cosMax, u1, u2);
    *coverage = 1 + holding(w, k);
    return w;
}

double ConeUnion::pdf(const Vec3& w) const {
    return mTotal > 0.0 ? holding(w, mCones.size()) / mTotal : 0.0;
}

DiscUnion::DiscUnion(std::vector<TargetSphere> spheres) : mSpheres(std::move(spheres)) {
    for (const TargetSphere& s : mSpheres) {
        mTotal += kPi * double(s.radius) * double(s.radius);
        mCdf.push_back(mTotal);
    }
}

size_t DiscUnion::pick(float u) const { return pickByCdf(mCdf, u); }

// A beam line through p along d crosses sphere j's disc where its distance from the centre,
// measured normal to d, is at most R_j.
int DiscUnion::holding(const Vec3& d, const Vec3& p, size_t except) const {
    int n = 0;
    for (size_t j = 0; j < mSpheres.size(); ++j) {
        const Vec3 off = p - mSpheres[j].centre;
        const Vec3 normal = off - d * dot(off, d);
        n += j != except && dot(normal, normal) <= mSpheres[j].radius * mSpheres[j].radius;
    }
    return n;
}

Vec3 DiscUnion::sample(const Vec3& d, float uPick, float u1, float u2, int* coverage) const {
    const size_t k = pick(uPick);
    const TargetSphere& s = mSpheres[k];
    const float rho = s.radius * std::sqrt(u1), phi = 2.f * kPi * u2;
    const Frame f(d);
    const Vec3 p = s.centre + f.s * (rho * std::cos(phi)) + f.t * (rho * std::sin(phi));
    *coverage = 1 + holding(d, p, k);
    return p;
}

double DiscUnion::pdf(const Vec3& d, const Vec3& p) const {
    return mTotal > 0.0 ? holding(d, p, mSpheres.size()) / mTotal : 0.0;
}

Vec3 upstreamOfScene(const Bounds3& scene, const Vec3& p, const Vec3& d) {
    const float r = 0.5f * length(scene.diagonal());
    return p + d * (dot(scene.center() - p, d) - 1.001f * r);
}

}  // namespace mirage
