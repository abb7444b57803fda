// A guess of the light a scattering point receives, to choose the points by.
//
// chooseScatterPoints (transport/scatter_point.h) resamples a camera walk's collisions into a
// few scattering points. Drawn ∝ T σs, the points fall where the medium is dense, whatever the
// light there: in a plume lit from one side, most land in its shadowed depth, and the error is
// mostly which points were drawn (docs/performance.md, "Where single scattering's error goes").
// Drawn ∝ T σs g instead, with g a positive guess of the direct light, they follow the light,
// and each is weighted by W/(K w̄ g) as before. Any g > 0 keeps the estimate unbiased
// (resampled importance sampling, Talbot et al. 2005: the selection probability cancels in the
// weight); a good g only lowers the variance. Here g is tabulated on a coarse grid over the
// media, one value per cell, read at the nearest cell.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

#include "core/math.h"

namespace mirage {

class ScatterGuide {
public:
    // Cells per axis: ~3 voxels of a 100-voxel cache per cell, 32³ cells to fill.
    static constexpr int kResolution = 32;
    // `values`: kResolution³ guesses at the cells' centres (x fastest), ≥ 0. None falls below
    // floorShare (> 0) of the largest, so that g > 0 everywhere (all 1 when every value is 0).
    ScatterGuide(const Bounds3& bounds, std::vector<float> values, float floorShare)
        : mBounds(bounds), mValues(std::move(values)) {
        const float top = mValues.empty() ? 0.f : *std::max_element(mValues.begin(), mValues.end());
        for (float& v : mValues) v = top > 0.f ? std::max(v, floorShare * top) : 1.f;
        const Vec3 d = bounds.diagonal();
        mScale = Vec3(kResolution / std::max(d.x, 1e-30f), kResolution / std::max(d.y, 1e-30f),
                      kResolution / std::max(d.z, 1e-30f));
    }

    // The centre of cell (i, j, k), world space.
    static Vec3 cellCentre(const Bounds3& bounds, int i, int j, int k) {
        const Vec3 d = bounds.diagonal();
        return bounds.lo +
               Vec3(d.x * (i + 0.5f), d.y * (j + 0.5f), d.z * (k + 0.5f)) / float(kResolution);
    }

    // g at a world point: the nearest cell's value (points outside clamp to the border).
    float at(const Vec3& p) const {
        const Vec3 q = (p - mBounds.lo) * mScale;
        const int i = cell(q.x), j = cell(q.y), k = cell(q.z);
        return mValues[size_t((k * kResolution + j) * kResolution + i)];
    }

private:
    static int cell(float x) { return std::clamp(int(x), 0, kResolution - 1); }

    Bounds3 mBounds;
    std::vector<float> mValues;
    Vec3 mScale;
};

}  // namespace mirage
