// The scattering point of a single-scattering estimate, chosen along the whole camera ray.
//
// Single scattering along a ray is L = ∫ T(t) σs(t) Ld(t) dt (Ld: the light in-scattered at t,
// phase and shadow included). Delta tracking estimates it by stopping at the first real
// collision: most samples of a thin pixel escape and score 0, the rest score Ld / albedo —
// a binary estimate whose relative variance is (1 − p)/p for a pixel of opacity p.
// Here the ray is followed to its end with ratio tracking instead (the same tentative
// collisions at rate σ̄, transmittance T_j ← T_j-1 (1 − σt/σ̄) per collision, Novák et al.
// 2014), which gives at every tentative collision j the weight w_j = T_j σs,j / σ̄j, with
// E[Σ_j w_j Ld(t_j)] = L. One collision is chosen by weighted reservoir sampling with
// probability w̄_j / W (w̄ the mean over the path's wavelengths, W = Σ w̄), and the estimate
// W (w_sel / w̄_sel) Ld(t_sel) has the same expectation: one shadow ray per sample, as delta
// tracking, at a point drawn ∝ T σs (delta tracking's distribution conditioned on scattering
// somewhere), with no escape and no absorption in the estimate. The reservoir draws one
// number (a stratified dimension with the Sobol sampler).
#pragma once

#include <vector>

#include "transport/scatter_guide.h"
#include "transport/tracking.h"

namespace mirage {

// Scattering points per camera ray, chosen by systematic resampling (one stratified uniform):
// each costs a shadow ray, and together they cover the ray's lit front and its shadowed depth.
constexpr int kScatterPoints = 4;

struct ScatterPointWalk {
    bool chosen = false;                  // a collision with σs > 0 was met
    Collision collision[kScatterPoints];  // the chosen ones (a collision may repeat)
    // W w_sel / (w̄_sel kScatterPoints): the factor of Ld at each chosen collision.
    SampledSpectrum weight[kScatterPoints];
    SampledSpectrum T{0.f};   // ratio-tracking transmittance over (0, tEnd); 0 when ended early
    bool reachedEnd = false;  // false: rouletted to 0 or cut at the collision cap
    // Σ mean(T σt / σ̄) over the collisions in holdout media: their share of the ray's
    // coverage 1 − T, which the pixel's alpha leaves out (0 without holdout media).
    float holdoutCoverage = 0.f;
};

// Where a walk's emission goes, weighted by beta, the path's throughput so far: summed into *L,
// or with `parts` (render passes, deep output), each collision's apart, with its distance along
// the ray.
struct EmissionAt {
    float t;
    SampledSpectrum L;
};
struct EmissionSink {
    SampledSpectrum beta;
    SampledSpectrum* L = nullptr;
    std::vector<EmissionAt>* parts = nullptr;
};

// Walks worldRay over (0, tEnd). Emission is scored into `emission` at every tentative
// collision (β T σa Le / σ̄, the collision estimator of ∫ T σa Le). A holdout medium
// (`holdouts`, indexed like ctx's media, RenderScene::mediumHoldouts; null or short: none there)
// only attenuates: it emits nothing and holds no scattering point. An observer
// sees every tentative collision the walk meets. With a guide (transport/scatter_guide.h), the
// points are drawn ∝ T σs g(p) instead of T σs and weighted by 1/g: the same expectation, less
// variance where g follows the light.
ScatterPointWalk chooseScatterPoints(TrackingContext& ctx, const Ray& worldRay, float tEnd,
                                     Sampler& sampler, const EmissionSink& emission,
                                     CollisionObserver* observer = nullptr,
                                     const ScatterGuide* guide = nullptr,
                                     const std::vector<bool>* holdouts = nullptr);

}  // namespace mirage
