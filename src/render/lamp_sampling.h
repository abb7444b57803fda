// Light from point, spot and sphere lights scattered off a path's segment, drawn two ways and
// combined by multiple importance sampling (Kulla & Fajardo 2012; Veach 1997 §9.2): the path
// tracer's own scattering points, drawn by delta tracking ∝ T σs, and one point per lamp drawn
// by equiangular sampling ∝ 1/r² towards it (transport/equiangular.h), over the part of the
// segment inside the media and inside a spot's cone. A sphere light is aimed at by its centre
// (its light falls off as 1/r² outside it, as a point's), and each strategy then estimates the
// light at its point by one direction drawn in the cone the sphere subtends.
//
// Both strategies estimate the single scattering of lamp k off the segment,
//     S_k = ∫ T(0, t) σs(t) p(θ) I_k V T(t, lamp) / r² dt,
// per medium m at t. Delta tracking's points fall with density σs,m(t) T(0, t); equiangular
// sampling's with p_e,k(t). The power heuristic weighs each point by its strategy's density
// against the other's, evaluated with the same function of t on both sides: for delta
// tracking the proxy q_m(t) = σs,m(t) (mean over the path's wavelengths; the transmittance
// factor is left out, since an estimate of it is random and a weight must not be). Any such
// pair of weights summing to 1 at every t keeps the sum unbiased (Veach 1997, eq. 9.3); the
// proxy only decides how well the variance is split. Near the lamp p_e grows as 1/r and takes
// the weight, where delta tracking's points made fireflies; far from it σs takes it back.
//
// The equiangular point's estimate: β T̂(0, t) σs,m(t) p(θ) Li T(t, lamp) / p_e(t), σs and p
// exact at t. Lamps beyond kMaxLamps, area lights and the dome keep next-event estimation at the
// scattering points alone (weight 1).
//
// T̂(0, t) comes from the path's own flight along the segment rather than a tracking pass of
// its own: the points are drawn before the flight. Its tentative collisions are a Poisson process
// of rate σ̄ whatever events it chooses, so the product of their ratio factors 1 − σt/σ̄ before t is
// ratio tracking's estimate of T(0, t) (Novák et al. 2014) at no extra lookup. Where the flight
// stops at τ < t (a real event), the process after τ is a fresh one (τ is a stopping time of it),
// and M(s) = Π_{points ≤ s} (1 − σt/σ̄) · T(s, t) is a martingale with M(0) = T(0, t): the product
// up to τ times any unbiased estimate of T(τ, t) drawn afterwards (residual ratio tracking)
// keeps E[T̂(0, t)] = T(0, t). Homogeneous media stay in closed form, their collisions left
// out of the product. The pass of its own cost about a seventh of the path tracer's
// instructions in the lamp-point regime (thin smoke, docs/regimes.md); where the flight passes
// the point, the flight's estimate costs no lookup at all.
#pragma once

#include <array>

#include "render/integrator.h"
#include "render/path_recorder.h"
#include "transport/equiangular.h"

namespace mirage {

class LampSampling {
public:
    // The lamps' segments along `ray` over (0, tEnd), clipped to the media's bounds and to each
    // spot's cone, and one point drawn on each. Empty where the scene has no point or spot
    // light, or `on` is false; then it draws nothing.
    LampSampling(const RenderScene& scene, const Ray& ray, float tEnd, bool on, Sampler& sampler);
    bool empty() const { return mCount == 0; }

    // The path's flight along the segment, which estimates the transmittance to the points:
    // each of its tentative collisions in order of t, then its end (reached: it got through
    // to tEnd without a real event).
    void seen(const Collision& c, const TrackingContext& tracking) {
        if (mCount) ratioTrack(c, tracking);
    }
    void flightEnded(bool reached);

    // The weight of next-event estimation to light `light` (an index into scene.lights) from a
    // scattering point that delta tracking found at c on this segment.
    float scatterPointWeight(size_t light, const Collision& c) const;

    // The equiangular points' estimate, one per lamp, each recorded as light gathered in the
    // medium at its t: beta is the path's throughput at the segment's start. After the flight.
    void gather(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                ThreadState& ts, PathRecorder& rec) const;

private:
    struct Lamp {
        size_t light;
        EquiangularSegment segment;
        float t = 0.f, pdf = 0.f;  // the point drawn, and its density (1/m)
        bool passed = false;       // the flight's estimate of T(0, t) is complete: ratio
        SampledSpectrum ratio{1.f};
    };
    static constexpr size_t kMaxLamps = 8;
    Ray mRay;
    std::array<Lamp, kMaxLamps> mLamps{};
    size_t mCount = 0;
    SampledSpectrum mRatio{1.f};  // the flight's ratio product so far
    float mLastT = 0.f;           // where the flight's last tentative collision was
    const Lamp* find(size_t light) const;
    void ratioTrack(const Collision& c, const TrackingContext& tracking);
    SampledSpectrum toPoint(const Lamp& lamp, TrackingContext& tracking, Sampler& sampler) const;
};

// Whether a scene's paths draw points towards its lamps: any point or spot light and the
// scene's `[render] lamp_sampling` (RenderScene::equiangular).
bool samplesLamps(const RenderScene& scene);

}  // namespace mirage
