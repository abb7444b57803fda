// The data passes of a camera sample (film/aov.h): what the camera ray meets, not the light it
// carries. Along the ray to its first surface, ratio tracking (Novák et al. 2014) gives at
// every tentative collision the transmittance T so far, and
//   transmittance   T at the ray's end (0 behind a surface: surfaces are opaque here)
//   albedo          Σ T σs / σ̄ (an unbiased estimate of ∫ T σs dt, the opacity-weighted
//                   single-scattering albedo ∫ T σt (σs/σt) dt) + T(surface) ρ(surface)
//   depth           the first collision where mean T falls to ½ (opacity 50 %), else the
//                   surface's distance, else ∞
// Glass and mirrors count as opaque surfaces (a denoiser wants the first hit), with the albedo
// of their BSDF's diffuse part (0).
//
// For deep output (film/deep.h) the same walk says where the ray's coverage builds up: the
// mean drop of T at each collision in a visible medium, and the T left at an opaque surface;
// for Cryptomatte (film/cryptomatte.h) the same, per medium and per surface, which the renderer
// scales to the beauty's alpha (AovSample::scaleCoverage).
//
// The walk is the integrator's own where it can be. Ratio tracking's T depends only on where
// the tentative collisions fall, not on what an estimator decides at them, and the beauty's
// walk of the camera ray meets the same Poisson process of tentative collisions at rate σ̄:
// `single` and `photon` follow it to its end (transport/scatter_point.h), `volpath` to its first
// real collision. The integrator hands each collision of that walk to seen() and says how the
// walk ended (walked()); finish() goes on alone from the last collision seen when the walk
// stopped at it — a stopping point chosen without looking ahead, from which a Poisson process
// may go on with fresh numbers — and walks the whole ray when no integrator walked it (curved
// camera rays). The data's own numbers (roulette, the rest of the walk) come from a stream of
// their own, so the beauty keeps its bits, and the data passes cost only the part of the ray
// the integrator did not walk.
#pragma once

#include "render/integrator.h"

namespace mirage {

class CameraRayData final : public CollisionObserver {
public:
    // Records into aov and deep (either may be null) for the camera ray `ray` at wavelengths w,
    // drawing its own numbers from `sampler`.
    CameraRayData(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                  Sampler& sampler, ThreadState& ts, AovSample* aov, DeepSample* deep);

    // A tentative collision of the integrator's walk of the camera ray, in order from the camera.
    void seen(const Collision& c) override;
    // The integrator's walk of the camera ray ended: at the ray's end (its first surface or
    // tMax), or stopped at the last collision it handed over.
    void walked(bool reachedEnd) { mWalk = reachedEnd ? Walk::ToTheEnd : Walk::Stopped; }
    // Completes the walk where the integrator's ended, adds the surface and writes the passes.
    void finish();

private:
    enum class Walk { None, Stopped, ToTheEnd };
    const RenderScene& mScene;
    const Ray& mRay;
    SampledWavelengths mW;
    Sampler& mSampler;
    ThreadState& mTs;
    AovSample* mAov;
    DeepSample* mDeep;
    bool mCrypto;
    Walk mWalk = Walk::None;
    SampledSpectrum mT{1.f}, mAlbedo{0.f};
    float mDepth = kInfinity;
    float mLastT = 0.f;  // the last collision seen
    bool mAlive = true;  // not ended by the roulette
};

}  // namespace mirage
