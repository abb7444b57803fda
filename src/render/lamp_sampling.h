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
// the rest see nothing: the pixel's noise is that of a coin of probability 1 − T. So the camera
// ray also draws, per medium, kSkyStrata points, one per stratum of its optical depth, as a
// march of SkyProfile::kSteps steps over the medium's box reads it: σt at each step's midpoint,
// constant over the step (render/sky_profile.h). The points are uniform in that depth τ̂, density
// p(t) = kSkyStrata σ̂(t) / τ̂ — the shape of delta tracking's own σt but stratified, and as many
// on a ray of depth 0.01 as on one of 10. Each point's term of the strata's sum is
// w_s(t) β T̂(0, t) σs(t) / p(t). One point is lit, by next-event estimation through both of the
// dome's strategies (render/direct_light.cpp): it is chosen in proportion to its term (with the
// transmittance the flight read where it got that far) and divided by the probability of its
// choice, an unbiased estimate of the sum for one shadow connection. Delta tracking's
// scattering points keep the rest: the two are weighed by the power heuristic with the
// densities p(t) and σs(t) (the proxy of delta tracking's, as for the lamps), evaluated alike on
// both sides, so w_s + w_dt = 1 at every t. On a thin ray p ≫ σs and the points take the light;
// on a deep one (τ̂ ≫ kSkyStrata), σs ≫ p and delta tracking does. The march decides nothing
// but densities and where the path forks, and is a function of the ray alone: the sum stays
// unbiased wherever it misreads the medium (a voxel between two midpoints: there p = 0 and
// delta tracking keeps the weight).
// Until 2026-11-30 the points were uniform in the majorant's optical depth D instead. Where the
// majorant is loose — the wisps of a cloud's edge beside denser voxels, D ≫ τ — they fell
// where σs ≪ σ̄ and left the wisps' dense voxels to delta tracking's coin; and a ray forked by D
// (below), so a thin ray beside dense cells did not fork. Sky-white at 32 samples (seeds 11 and
// 12, relMSE against the reference): 0.0086 by the majorant, 0.0065 by the march (64 steps, a
// fork where τ̂ ≤ 2); the edges of alpha < 0.03 0.044 → 0.022 per pixel.
//
// Forks (skyPointsFork: one medium, neither emissive nor fluorescent, no surfaces, domes alone).
// The path also goes on from the lit point: a second path whose throughput is its estimate's
// weight, and which carries the light scattered more than once off the camera ray's thin stretches.
// The lit point then leaves the lights' phase-function strategy to that path's escape, as every
// vertex past the camera ray does (MediumLights::SkyByEscape; a uniform dome by the escape alone):
// one direction then carries the sky where it is open and the cloud's light where it is not. The
// point's own shadow ray had scored the open sky or nothing, a coin beside the second path
// (sky-white, 32 samples: relMSE 0.0054 → 0.0038, CPU −14 %; alpha 0.1–0.3 0.020 → 0.0042 per
// pixel). Delta tracking's scattering point then goes on only with probability w_dt(t), its weight
// taken as a roulette. A ray of marched depth above kForkDepth forks nothing: there delta
// tracking's points take most of the light, and a second path of large weight costs more variance
// than it saves. The second path's roulette measures its throughput against the weight it started
// with (PathThroughput::rouletteScale): on a ray of alpha 0.02 the lit point's weight is ~0.02, and
// a roulette against 1 kept one such path in five at 0.25 — the pixel's multiple scattering a coin
// again (sky-white, 32 samples: relMSE 0.0065 → 0.0054; alpha < 0.03 0.022 → 0.0046 per pixel).
// Sky-white, noise between two seeds at 32 samples, by the fork's depth τ̂ (with the majorant's
// points and forks the day before, 16: 0.0086): 1, 0.0065; 2, 0.0065; 5, 0.0075; 16, 0.0084.
// Where paths are guided (a forward medium under a sun, or a sky map with one: render/
// light_lobes.h) the points and forks are drawn too, and the second path is guided as the first
// (volpath's forkAt); sky-hdr at 16 samples, τ̂ 2 and 4 alike (relMSE 0.205 and 0.205).
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
#include <optional>
#include <type_traits>

#include "render/direct_light.h"
#include "render/integrator.h"
#include "render/path_recorder.h"
#include "render/sky_profile.h"
#include "transport/equiangular.h"

namespace mirage {

// The camera ray's scattering as the points for the lights at infinity drew it, where the
// path goes on from there (skyPointsFork): the point, the path's throughput at it, and how its
// estimate drew the lights' own samples: their phase-function strategy is the second path's
// escape (MediumLights::SkyByEscape), as at every other vertex.
struct SkyFork {
    Collision at;
    SampledSpectrum beta;
    SkyDraws sky;
};

class LampSampling {
public:
    // The lamps' segments along `ray` over (0, tEnd), clipped to the media's bounds and to each
    // spot's cone, and one point drawn on each; with `sky` (the camera ray's tracking context),
    // one point per medium for the lights at infinity too. Empty where the scene has no point
    // or spot light, or `on` is false, and no `sky`; then it draws nothing.
    // With `forks` (skyPointsFork), the path goes on from the point that took the lights at
    // infinity as well as from delta tracking's (gather, keepsScatterPoint).
    LampSampling(const RenderScene& scene, const Ray& ray, float tEnd, bool on, Sampler& sampler,
                 TrackingContext* sky = nullptr, bool forks = false);
    bool empty() const { return mCount == 0 && mSkyCount == 0; }
    // Where the points fork: whether the path goes on from delta tracking's scattering point
    // at c, with the probability of its weight against the points (lamp_sampling.h).
    bool keepsScatterPoint(const Collision& c, Sampler& sampler) const;

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
    // The weight of the lights at infinity at such a point against the segment's points for
    // them (the power heuristic; 1 where it drew none, or where they fork): what its
    // next-event estimate of them carries, and its continuation's escape where it leaves them
    // to it (render/direct_light.h: MediumLights::SkyByEscape).
    float skyWeight(const Collision& c) const;

    // The points' estimates, one per lamp and one per medium for the lights at infinity, each
    // recorded as light gathered in the medium at its t: beta is the path's throughput at the
    // segment's start. After the flight.
    // Where the points fork, *fork receives the point the path goes on from, if any.
    void gather(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                ThreadState& ts, PathRecorder& rec, std::optional<SkyFork>* fork = nullptr) const;

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
    // A medium's points for the lights at infinity: one per stratum of the profile's optical
    // depth, `count` of them (fewer where rounding ends the march).
    static constexpr int kSkyStrata = 4;
    struct SkyPoint {
        int medium;
        SkyProfile profile;
        int count = 0;
        std::array<FlightPoint, kSkyStrata> points;
        // The strata's density of points at t (1/m): kSkyStrata σ̂(t) / τ̂.
        float density(float t) const {
            return float(kSkyStrata) * profile.at(t) / profile.depth;
        }
    };
    static constexpr size_t kMaxSky = 4;  // media beyond keep their scattering points' alone
    // The points' storage, left unconstructed until a point is drawn (as trackCollisions'
    // streams): every segment of a path makes a LampSampling, and past the camera's, in a
    // sky-lit cloud, none draws a point; clearing the kilobyte of both arrays was ~3 % of the
    // sky-white regime's core (perf). Entries [0, mSkyCount) and [0, mCount) are constructed.
    template <typename T, size_t N>
    union Storage {
        Storage() {}
        std::array<T, N> at;
        static_assert(std::is_trivially_destructible_v<T>);
    };
    Storage<SkyPoint, kMaxSky> mSky;
    size_t mSkyCount = 0;
    void drawSky(TrackingContext& tracking, float tEnd, Sampler& sampler);
    bool mForks = false;
    void gatherSky(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                   ThreadState& ts, PathRecorder& rec, std::optional<SkyFork>* fork) const;
    static constexpr size_t kMaxLamps = 8;
    Ray mRay;
    const RenderScene* mScene = nullptr;
    Storage<Lamp, kMaxLamps> mLamps;
    size_t mCount = 0;
    SampledSpectrum mRatio{1.f};  // the flight's ratio product so far
    float mLastT = 0.f;           // where the flight's last tentative collision was
    const Lamp* find(size_t light) const;
    const SkyPoint* findSky(int medium) const;
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
// Whether the paths also go on from those points (lamp_sampling.h): where they draw them and
// every light is a dome (Light::infinite: a distant sun is not), one medium, neither emissive
// nor fluorescent, and no surface.
bool skyPointsFork(const RenderScene& scene);

}  // namespace mirage
