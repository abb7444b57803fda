// Light from point, spot and sphere lights, and from the dome, scattered off a path's segment,
// drawn two ways and combined by multiple importance sampling (Kulla & Fajardo 2012; Veach 1997
// §9.2): the path tracer's own scattering points, drawn by delta tracking ∝ T σs, and one point
// per lamp drawn by equiangular sampling ∝ 1/r² towards it (transport/equiangular.h), over the
// part of the segment inside the media and inside a spot's cone. A sphere light is aimed at by
// its centre (its light falls off as 1/r² outside it, as a point's), and each strategy then
// estimates the light at its point by one direction drawn in the cone the sphere subtends.
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
// exact at t. Lamps beyond kMaxLamps and area lights keep next-event estimation at the
// scattering points alone (weight 1).
//
// The lights at infinity (the dome) on the camera ray. Where the camera ray crosses thin
// medium (a cloud's edge), delta tracking scatters on a few of its samples (1 − T of them) and
// the rest see nothing: the pixel's noise is that of a coin of probability 1 − T, a tenth of
// the relMSE of a white-dome cloud in its darkest quarter of pixels. So the camera ray also
// draws, per medium, a point t from the majorant's exponential truncated to the segment's
// first kSkyDepthCap of majorant optical depth (ending at t_cap): density
//     p_s(t) = σ̄(t) e^{−τ̄(0, t)} / (1 − e^{−τ̄(0, t_cap)}),
// the flight's first tentative collision forced to fall there. It takes all of the dome's
// single scattering over (0, t_cap), next-event estimation through both of the dome's
// strategies (render/direct_light.cpp); delta tracking's scattering points keep it past t_cap
// (weights 0 and 1, a partition fixed by the ray: unbiased). Its estimate,
// β T̂(0, t) σs,m(t) L_dome(t) / p_s(t), is bounded by about e^{kSkyDepthCap} T̂ where the
// majorant is loose over long stretches; the cap keeps that small. Measured on the sky-white
// regime (16 samples, 6 seeds): relMSE 0.194 → 0.140 for 7 % more lookups at a cap of 3 (0.147
// at 2, 0.145 at 4; at 8, fireflies: 0.26). On later segments the same points cost more than
// they saved (0.151 for 1.3× the CPU time at a cap of 1).
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
    // spot's cone, and one point drawn on each; with `sky` (the camera ray's tracking context),
    // one point per medium for the lights at infinity too. Empty where the scene has no point
    // or spot light, or `on` is false, and no `sky`; then it draws nothing.
    LampSampling(const RenderScene& scene, const Ray& ray, float tEnd, bool on, Sampler& sampler,
                 TrackingContext* sky = nullptr);
    bool empty() const { return mCount == 0 && mSkyCount == 0; }
    // Whether points were drawn for the lights at infinity (the camera ray).
    bool drewSky() const { return mSkyCount > 0; }

    // The path's flight along the segment, which estimates the transmittance to the points:
    // each of its tentative collisions in order of t, then its end (reached: it got through
    // to tEnd without a real event).
    void seen(const Collision& c, const TrackingContext& tracking) {
        if (mCount || mSkyCount) ratioTrack(c, tracking);
    }
    void flightEnded(bool reached);

    // The weight of next-event estimation to light `light` (an index into scene.lights) from a
    // scattering point that delta tracking found at c on this segment: 0 for a light at
    // infinity where the segment's point of c's medium takes its light.
    float scatterPointWeight(size_t light, const Collision& c) const;

    // The points' estimates, one per lamp and one per medium for the lights at infinity, each
    // recorded as light gathered in the medium at its t: beta is the path's throughput at the
    // segment's start. After the flight.
    void gather(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                ThreadState& ts, PathRecorder& rec) const;

private:
    struct FlightPoint {
        float t = 0.f, pdf = 0.f;  // the point drawn, and its density (1/m)
        bool passed = false;       // the flight's estimate of T(0, t) is complete: ratio
        SampledSpectrum ratio{1.f};
    };
    struct Lamp {
        size_t light;
        EquiangularSegment segment;
        FlightPoint point;
    };
    // A medium's point for the lights at infinity, taking their light over (0, tCap).
    struct SkyPoint {
        int medium;
        float tCap;
        FlightPoint point;
    };
    static constexpr size_t kMaxSky = 4;  // media beyond keep their scattering points' alone
    std::array<SkyPoint, kMaxSky> mSky{};
    size_t mSkyCount = 0;
    void drawSky(TrackingContext& tracking, float tEnd, Sampler& sampler);
    void gatherSky(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                   ThreadState& ts, PathRecorder& rec) const;
    static constexpr size_t kMaxLamps = 8;
    Ray mRay;
    const RenderScene* mScene = nullptr;
    std::array<Lamp, kMaxLamps> mLamps{};
    size_t mCount = 0;
    SampledSpectrum mRatio{1.f};  // the flight's ratio product so far
    float mLastT = 0.f;           // where the flight's last tentative collision was
    const Lamp* find(size_t light) const;
    // Every point before t not yet passed takes the flight's ratio product so far.
    void passPoints(float t);
    void ratioTrack(const Collision& c, const TrackingContext& tracking);
    SampledSpectrum toPoint(const FlightPoint& lamp, TrackingContext& tracking,
                            Sampler& sampler) const;
};

// Whether a scene's paths draw points towards its lamps: any point or spot light and the
// scene's `[render] lamp_sampling` (RenderScene::equiangular).
bool samplesLamps(const RenderScene& scene);
// Whether its camera rays draw points for the lights at infinity: a dome, a medium, and
// `[render] lamp_sampling` = equiangular.
bool samplesSky(const RenderScene& scene);

}  // namespace mirage
