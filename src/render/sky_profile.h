// The camera ray's optical depth as the points for the lights at infinity read it
// (render/lamp_sampling.h): a march of kSteps over a medium's box, σt at each step's midpoint
// (the mean over the path's wavelengths), constant over the step, and the points drawn
// uniformly in its depth, one per stratum. The march shapes densities and decides where a
// path forks; it estimates nothing, so the points' sum stays unbiased wherever it misreads the
// medium (a voxel between two midpoints: there the points' density is 0 and delta tracking's
// points keep the weight).
#pragma once

#include <array>

#include "core/math.h"
#include "medium/medium.h"

namespace mirage {

struct SkyProfile {
    // Sky-white, 32 samples: 32, 64 and 128 steps within the noise of each other.
    static constexpr int kSteps = 32;
    float start = 0.f, step = 0.f;  // object-space ray parameter of the first step, its length
    float depth = 0.f;              // Σ σ̂ · step
    std::array<float, kSteps> sigma{};

    // σt along the object-space ray r over [a, b] (inside medium's box), in its context.
    static SkyProfile march(const Medium& medium, Medium::Context& ctx, const Ray& r, float a,
                            float b);
    // The march's σ̂ at t (0 outside the steps).
    float at(float t) const {
        const float k = (t - start) / step;
        return k >= 0.f && k < float(kSteps) ? sigma[size_t(k)] : 0.f;
    }
    // `strata` points, the i-th at depth (i + u) depth / strata: t[i] and the strata's density
    // there, pdf[i] = strata σ̂(t) / depth (1/m). Returns how many were placed (fewer where
    // rounding ends the steps first); none where depth is 0.
    int stratify(float u, int strata, float* t, float* pdf) const;
};

}  // namespace mirage
