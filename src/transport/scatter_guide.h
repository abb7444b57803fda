// A guess of the light a scattering point receives, to choose the points by.
//
// chooseScatterPoints (transport/scatter_point.h) resamples a camera walk's collisions into a
// few scattering points. Drawn ∝ T σs, the points fall where the medium is dense, whatever the
// light there: in a plume lit from one side, most land in its shadowed depth, and the error is
// mostly which points were drawn (docs/performance-history.md, "Where single scattering's error
// goes").
// Drawn ∝ T σs g instead, with g a positive guess of the direct light, they follow the light,
// and each is weighted by W/(K w̄ g) as before. Any g > 0 keeps the estimate unbiased
// (resampled importance sampling, Talbot et al. 2005: the selection probability cancels in the
// weight); a good g only lowers the variance. Here g is tabulated on a coarse grid over the
// media, one value per cell's centre, interpolated between them (render/scatter_guide_build.h
// fills it).
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

#include "core/math.h"

namespace mirage {

class ScatterGuide {
public:
    // `values`: resolution³ guesses at the cells' centres (x fastest), ≥ 0. None falls below
    // floorShare (> 0) of the largest, so that g > 0 everywhere (all 1 when every value is 0).
    // resolution ≥ 2.
    ScatterGuide(const Bounds3& bounds, int resolution, std::vector<float> values, float floorShare)
        : mBounds(bounds), mRes(resolution), mValues(std::move(values)) {
        const float top = mValues.empty() ? 0.f : *std::max_element(mValues.begin(), mValues.end());
        for (float& v : mValues) v = top > 0.f ? std::max(v, floorShare * top) : 1.f;
        const Vec3 d = bounds.diagonal();
        mScale = Vec3(mRes / std::max(d.x, 1e-30f), mRes / std::max(d.y, 1e-30f),
                      mRes / std::max(d.z, 1e-30f));
    }

    int resolution() const { return mRes; }

    // The centre of cell (i, j, k) of a grid of n³ cells over `bounds`, world space.
    static Vec3 cellCentre(const Bounds3& bounds, int n, int i, int j, int k) {
        const Vec3 d = bounds.diagonal();
        return bounds.lo + Vec3(d.x * (i + 0.5f), d.y * (j + 0.5f), d.z * (k + 0.5f)) / float(n);
    }

    // g at a world point, interpolated trilinearly between the cells' centres (points outside
    // clamp to the border): a smooth g moves the points' density smoothly with the light,
    // where the nearest cell's value steps at every cell face (11 % more relMSE on the race
    // scene, docs/performance-history.md, "The light guide without shadow rays").
    float at(const Vec3& p) const {
        const Vec3 q = (p - mBounds.lo) * mScale;
        int i, j, k;
        float fx, fy, fz;
        corner(q.x, &i, &fx);
        corner(q.y, &j, &fy);
        corner(q.z, &k, &fz);
        const size_t dy = size_t(mRes), dz = size_t(mRes) * mRes;
        const float* v = &mValues[k * dz + j * dy + size_t(i)];
        auto lerp = [](float a, float b, float f) { return a + f * (b - a); };
        auto row = [&](size_t o) { return lerp(v[o], v[o + 1], fx); };
        return lerp(lerp(row(0), row(dy), fy), lerp(row(dz), row(dz + dy), fy), fz);
    }

private:
    // The lower of the two cell centres around x (in cells from the low face) and the fraction
    // of the way to the upper one; the guide has at least 2 cells per axis.
    void corner(float x, int* i0, float* f) const {
        const float c = x - 0.5f > 0.f ? std::min(x - 0.5f, float(mRes - 1)) : 0.f;  // NaN: 0
        *i0 = std::min(int(c), mRes - 2);
        *f = c - float(*i0);
    }

    Bounds3 mBounds;
    int mRes;
    std::vector<float> mValues;
    Vec3 mScale;
};

}  // namespace mirage
