// The data passes of a camera sample (film/aov.h): what the camera ray meets, not the light it
// carries. Along the ray to its first surface, ratio tracking (Novák et al. 2014) gives at
// every tentative collision the transmittance T so far, and
//   transmittance   T at the ray's end (0 behind a surface: surfaces are opaque here)
//   albedo          Σ T σs / σ̄ (an unbiased estimate of ∫ T σs dt, the opacity-weighted
//                   single-scattering albedo ∫ T σt (σs/σt) dt) + T(surface) ρ(surface)
//   depth           the first collision where mean T falls to ½ (opacity 50 %), else the
//                   surface's distance, else ∞
// The walk draws its numbers from a stream of its own, so the beauty keeps its bits; it runs
// only when one of these passes is asked for. Glass and mirrors count as opaque surfaces (a
// denoiser wants the first hit), with the albedo of their BSDF's diffuse part (0).
//
// For deep output (film/deep.h) the same walk says where the ray's coverage builds up: the
// mean drop of T at each collision in a visible medium, and the T left at an opaque surface;
// for Cryptomatte (film/cryptomatte.h) the same, per medium and per surface, which the renderer
// scales to the beauty's alpha (AovSample::scaleCoverage).
#pragma once

#include "render/integrator.h"

namespace mirage {

// Either of aov and deep may be null.
void cameraRayData(const RenderScene& scene, const Ray& ray, Sampler& sampler, ThreadState& ts,
                   AovSample* aov, DeepSample* deep);

}  // namespace mirage
