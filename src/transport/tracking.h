// Free-flight sampling and transmittance, written once for every integrator.
//
// Null-collision formulation (Woodcock tracking; Novák et al. 2014; Kutz et al. 2017): each
// medium is a Poisson process of tentative collisions with rate σ̄ from its majorant grid.
// σ̄ is grey (the maximum over wavelengths), so the exponential terms of all wavelengths are
// identical and cancel in every weight; at a tentative collision the caller decides between
// absorption (σa), real scattering (σs) and a null collision (σn = σ̄ − σa − σs). Several media
// are superposed exactly: the union of independent Poisson processes is the process of the
// summed rate, so the next collision of the scene is the earliest of each medium's next.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "medium/medium.h"

namespace mirage {

// Tentative collisions per free flight before it is cut (~10 ms of one core): far above what
// a majorant within a factor 100 of σt needs (a flight meets a real collision after ~100
// tentative ones), low enough that a degenerate one ends. A hot voxel (σ = 1e10/m) makes its
// whole majorant cell that dense: every ray through the cell would otherwise take ~1e9 steps.
constexpr uint64_t kMaxCollisionsPerFlight = uint64_t(1) << 16;

// Per-thread tracking state: one Medium::Context per medium, plus counters for the summary.
class TrackingContext {
public:
    explicit TrackingContext(const std::vector<const Medium*>& media);
    void setWavelengths(const SampledWavelengths& w);
    const SampledWavelengths& wavelengths() const { return mLambda; }
    // The path's time relative to the frame (seconds, motion blur): every medium lookup on the
    // path is made at it (Medium::Context::setTimeOffset).
    void setTimeOffset(float seconds);
    float timeOffset() const { return mTime; }
    size_t size() const { return mMedia.size(); }
    const Medium& medium(size_t i) const { return *mMedia[i]; }
    Medium::Context& context(size_t i) { return mContexts[i]; }
    // The majorant a homogeneous medium is tracked with at the current wavelengths: max_i σt(λ_i)
    // (its σt is the same everywhere, so that bounds it exactly), instead of its grid's maximum
    // over all wavelengths. For a photon (four equal wavelengths) it is σt(λ) itself, and delta
    // tracking meets no null collision: in sea water, whose grey majorant is set by 2.7 1/m of
    // absorption at 780 nm, a blue photon otherwise meets ~70 null collisions per real event.
    // Negative for a medium with a grid.
    float pathMajorant(size_t i) const { return mPathMajorant[i]; }

    uint64_t lookups = 0;  // medium evaluations (each reads every grid of the shader)
    // Free flights cut at maxCollisions tentative collisions (a bias, reported as capped
    // paths). The cap bounds time where the majorant dwarfs σt over long distances, e.g. one
    // voxel of σ = 1e6/m inside a kilometre-wide majorant cell (1e9 null collisions per ray).
    uint64_t cappedFlights = 0;
    uint64_t maxCollisions = kMaxCollisionsPerFlight;
    // Tentative collisions whose σt (at any of the path's wavelengths) exceeded the majorant
    // they were sampled with: each one biases delta and ratio tracking, so the count must be 0
    // (it checks the majorant, e.g. the one dilated for motion blur, on every lookup).
    uint64_t aboveMajorant = 0;

private:
    std::vector<const Medium*> mMedia;
    std::vector<Medium::Context> mContexts;
    std::vector<float> mPathMajorant;
    SampledWavelengths mLambda;
    float mTime = 0.f;
};

// Next tentative collision of one medium along its walk of the majorant grid, after the last
// one at t: walks on until the optical depth of the majorant reaches tau (an Exp(1) sample),
// and leaves the walk there. Returns false when the ray leaves the medium (or passes the walk's
// end) first. pathMajorant ≥ 0 replaces the grid's value (a homogeneous medium's one cell, at
// the path's wavelengths: TrackingContext::pathMajorant).
bool nextTentativeCollision(MajorantGrid::Walk& walk, float t, float tau, float* tHit,
                            float* sigmaMaj, float pathMajorant = -1.f);

// An Exp(1) draw, the optical depth to the next tentative collision: −ln(1 − u). 1 − u is exact
// for the sampler's 24-bit u, so logf loses nothing against log1pf and costs less (glibc's
// logf is table-driven; log1pf is not).
inline float exponentialDraw(Sampler& sampler) { return -std::log(1.f - sampler.get1D()); }

enum class Track { Continue, Stop };

// A tentative collision handed to the caller of trackCollisions.
struct Collision {
    int medium;      // index into the context
    float t;         // world ray parameter (m)
    Vec3 p;          // world position
    float sigmaMaj;  // majorant at the collision (1/m)
    MediumPoint mp;  // coefficients at the path's wavelengths
};

// Sees, in order, the tentative collisions of a walk that another estimator makes along the
// same ray: the camera ray's data passes read them off an integrator's walk instead of walking
// the ray again (render/camera_ray_data.h).
class CollisionObserver {
public:
    virtual void seen(const Collision& c) = 0;

protected:
    ~CollisionObserver() = default;
};

// Calls f(const Collision&) at every tentative collision along worldRay in (0, tMax), in
// increasing t, until f returns Track::Stop. Returns true when the ray got through to tMax
// without being stopped; false too when the flight hit ctx.maxCollisions (ctx.cappedFlights
// is then incremented: callers treat the flight as absorbed).
template <typename F>
bool trackCollisions(TrackingContext& ctx, const Ray& worldRay, float tMax, Sampler& sampler,
                     F&& f);

// Transmittance along worldRay over (0, tMax): the closed form exp(−σt(λ)·d) for homogeneous
// media, residual ratio tracking for the others — unbiased, with Russian roulette once it
// falls below 0.05. The product of the two parts below.
SampledSpectrum transmittance(TrackingContext& ctx, const Ray& worldRay, float tMax,
                              Sampler& sampler);
// The homogeneous media's part alone (Medium::closedFormTransmittance): exact.
SampledSpectrum closedFormTransmittance(TrackingContext& ctx, const Ray& worldRay, float tMax);
// The other media's part alone, by residual ratio tracking.
SampledSpectrum trackedTransmittance(TrackingContext& ctx, const Ray& worldRay, float tMax,
                                     Sampler& sampler);

// Russian roulette on a transmittance estimate once it falls below 0.05: survives with
// probability 1 − q = 1/4 and is reweighted by 1/(1 − q). False (and T = 0) when it ends.
bool russianRoulette(SampledSpectrum* T, Sampler& sampler);

// Residual ratio tracking (Novák et al. 2014, "Residual ratio tracking for estimating
// attenuation in participating media") through medium i alone. In each majorant cell the ray
// crosses, a control σc (σt at the middle of the ray's segment in the cell) is integrated in
// closed form, exp(−σc ℓ), and only the residual σt − σc is tracked, at a rate σ̄r chosen so
// that every factor 1 − (σt − σc)/σ̄r lies in [0, 2]. E[Π factors] = exp(−∫(σt − σc)) for any
// σc that does not depend on the random numbers, so the product is unbiased; where σt varies
// little within a cell (the inside of dense smoke, where plain ratio tracking multiplies many
// factors near 0) the factors stay near 1 and the estimate is nearly deterministic.
SampledSpectrum residualRatioTracking(TrackingContext& ctx, size_t i, const Ray& worldRay,
                                      float tMax, Sampler& sampler);

// Null-collision weight factors for the three events of one tentative collision: the
// per-wavelength σ/σ̄ and the probabilities of choosing each event. Spectral tracking (Kutz et
// al. 2017, history-aware): P_x ∝ max_i β_i σ_x(λ_i) over the path's wavelengths, x ∈
// {absorption, scattering, null}, β the path's throughput so far. Every event with a non-zero
// σ at a live wavelength can be chosen, so every estimator stays unbiased, and the weights
// β_i σ_x(λ_i) / (σ̄ P_x) stay bounded. With plain means over wavelengths, a wavelength far
// below the grey majorant (blue light in water, whose σ̄ is set by its 2.7 1/m absorption at
// 780 nm) gains a factor σn,i / mean σn > 1 at every null collision, and its variance grows
// exponentially with the distance tracked. With equal wavelengths (a photon) the probabilities
// are σ_x/σ̄ as before.
struct EventProbabilities {
    SampledSpectrum sigmaN;  // σ̄ − σa − σs, per wavelength
    float pAbsorb, pScatter, pNull;
};
EventProbabilities eventProbabilities(const Collision& c,
                                      const SampledSpectrum& beta = SampledSpectrum(1.f));

}  // namespace mirage

#include "transport/tracking.inl"
