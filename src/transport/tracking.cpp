#include "transport/tracking.h"

namespace mirage {

TrackingContext::TrackingContext(const std::vector<const Medium*>& media) : mMedia(media) {
    mContexts.reserve(media.size());
    for (const Medium* m : media) mContexts.emplace_back(*m);
    mPathMajorant.assign(media.size(), -1.f);
}

void TrackingContext::setWavelengths(const SampledWavelengths& w) {
    mLambda = w;
    for (size_t i = 0; i < mContexts.size(); ++i) {
        mContexts[i].setWavelengths(w);
        const Medium& m = *mMedia[i];
        if (!m.homogeneous()) continue;
        MediumPoint mp;
        // Unconfined: the box's centre may lie in a shape the medium is cut out of.
        m.evalUnconfined(m.objectBounds().center(), mContexts[i], &mp);
        float sigmaT = 0.f;
        for (int k = 0; k < kSpectrumSamples; ++k)
            sigmaT = std::max(sigmaT, mp.sigmaA[k] + mp.sigmaS[k]);
        // Never above the grid's value (its maximum over all wavelengths); a hair above σt so
        // that rounding cannot make σn negative.
        mPathMajorant[i] = std::min(m.majorant().maxValue(), sigmaT * (1.f + 1e-6f));
    }
}

void TrackingContext::setTimeOffset(float seconds) {
    mTime = seconds;
    for (auto& c : mContexts) c.setTimeOffset(seconds);
}

bool nextTentativeCollision(MajorantGrid::Walk& walk, float t, float tau, float* tHit,
                            float* sigmaMaj, float pathMajorant) {
    for (MajorantGrid::Walk::Segment s; walk.next(&s); walk.advanceTo(s.t1)) {
        const float sigma = pathMajorant >= 0.f ? pathMajorant : s.sigmaMaj;
        if (!(sigma > 0.f)) continue;    // empty cell: no collisions
        const float need = tau / sigma;  // distance at which the majorant's optical depth is tau
        if (need < s.t1 - s.t0) {
            // A collision at exactly the last one (need = 0 from tau = 0) would stall the walk.
            *tHit = s.t0 + need > t ? s.t0 + need : std::nextafter(t, kInfinity);
            *sigmaMaj = sigma;
            walk.advanceTo(*tHit);
            return true;
        }
        tau -= sigma * (s.t1 - s.t0);
    }
    return false;
}

EventProbabilities eventProbabilities(const Collision& c, const SampledSpectrum& beta) {
    EventProbabilities e;
    SampledSpectrum sigmaMaj(c.sigmaMaj);
    e.sigmaN = sigmaMaj - c.mp.sigmaA - c.mp.sigmaS;
    // A majorant that underestimates σt (it must not; see majorant tests) would make σn
    // negative: it is clamped here so the walk still ends.
    float a = 0.f, s = 0.f, n = 0.f;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        const float b = std::abs(beta[i]);
        a = std::max(a, b * c.mp.sigmaA[i]);
        s = std::max(s, b * c.mp.sigmaS[i]);
        n = std::max(n, b * std::max(0.f, e.sigmaN[i]));
    }
    if (!(a + s + n > 0.f)) {
        // A dead path (β = 0): any choice will do, every weight is 0.
        a = c.mp.sigmaA.average();
        s = c.mp.sigmaS.average();
        n = std::max(0.f, e.sigmaN.average());
    }
    const float sum = a + s + n;
    if (sum > 0.f) {
        e.pAbsorb = a / sum;
        e.pScatter = s / sum;
        e.pNull = n / sum;
    } else {
        e.pAbsorb = e.pScatter = 0.f;
        e.pNull = 1.f;
    }
    return e;
}

bool russianRoulette(SampledSpectrum* T, Sampler& sampler) {
    const float maxT = T->maxValue();
    if (maxT <= 0.f) {
        *T = SampledSpectrum(0.f);
        return false;
    }
    if (maxT < 0.05f) {
        constexpr float q = 0.75f;
        if (sampler.get1D() < q) {
            *T = SampledSpectrum(0.f);
            return false;
        }
        *T /= (1.f - q);
    }
    return true;
}

SampledSpectrum closedFormTransmittance(TrackingContext& ctx, const Ray& worldRay, float tMax) {
    // Homogeneous media have Beer–Lambert's closed form, exp(−σt(λ) ℓ) with ℓ the length of the
    // ray inside the box (t is world metres in object space too, see
    // Medium::Context::toObject): exact and noiseless (docs/design.md, "homogeneous closed-form
    // transmittance where a medium is constant"). Optical depths add over superposed media.
    SampledSpectrum tau(0.f);
    for (size_t i = 0; i < ctx.size(); ++i) {
        const Medium& m = ctx.medium(i);
        if (!m.closedFormTransmittance()) continue;
        Ray r = ctx.context(i).toObject(worldRay);
        float t0, t1;
        if (!m.objectBounds().intersect(r.o, r.d, 0.f, tMax, &t0, &t1) || !(t1 > t0)) continue;
        // A medium confined to a convex region: the chord through region ∩ box.
        if (!m.confinement().clip(worldRay, &t0, &t1) || !(t1 > t0)) continue;
        MediumPoint mp;
        m.eval(r.at(0.5f * (t0 + t1)), ctx.context(i), &mp);  // inside box and region
        tau += (mp.sigmaA + mp.sigmaS) * (t1 - t0);
    }
    return exp(tau * -1.f);
}

SampledSpectrum trackedTransmittance(TrackingContext& ctx, const Ray& worldRay, float tMax,
                                     Sampler& sampler) {
    // Medium by medium: optical depths add, so their transmittances multiply.
    SampledSpectrum T(1.f);
    for (size_t i = 0; i < ctx.size() && T.maxValue() > 0.f; ++i)
        if (!ctx.medium(i).closedFormTransmittance())
            T *= residualRatioTracking(ctx, i, worldRay, tMax, sampler);
    return T;
}

SampledSpectrum transmittance(TrackingContext& ctx, const Ray& worldRay, float tMax,
                              Sampler& sampler) {
    const SampledSpectrum T = closedFormTransmittance(ctx, worldRay, tMax);
    return T.maxValue() > 0.f ? T * trackedTransmittance(ctx, worldRay, tMax, sampler) : T;
}

// The majorant optical depth σ̄ℓ of a ray's segment through a majorant cell below which its
// control is 0. A control costs one lookup; plain ratio tracking (σc = 0, rate σ̄) expects σ̄ℓ of
// them in the segment, and residual tracking still σ̄r ℓ ≥ σ̄ℓ / 2 besides the control: below
// σ̄ℓ = 1 the control costs more lookups than it saves. Thin smoke, a plume's edges and the
// corners of cells a ray only clips are such segments: in the lamp-point regime (thin smoke,
// docs/regimes.md) three in four of the shadow rays' lookups were controls. The rule is a
// function of the ray alone, so the estimate stays unbiased; its variance in a thin segment is
// at most about σ̄ℓ (σt/σ̄)² relative.
constexpr float kThinCell = 1.f;

SampledSpectrum residualRatioTracking(TrackingContext& ctx, size_t i, const Ray& worldRay,
                                      float tMax, Sampler& sampler) {
    const Medium& m = ctx.medium(i);
    Medium::Context& mc = ctx.context(i);
    const Ray r = mc.toObject(worldRay);
    SampledSpectrum T(1.f);
    float tau = exponentialDraw(sampler);  // majorant optical depth to the next collision
    uint64_t collisions = 0;
    bool capped = false;
    m.majorant().traverse(r.o, r.d, 0.f, tMax, [&](float t0, float t1, float sigmaMaj) {
        if (!(sigmaMaj > 0.f)) return true;  // empty cell: T unchanged
        // The control: σt at the middle of the segment, a function of the ray alone, clamped
        // into [0, σ̄] per wavelength. Any such function keeps the estimate unbiased; for a
        // moving medium it is the still medium's σt there, which costs no velocity lookup
        // (most of a blurred shadow ray's lookups are controls). On the Mantaflow cache that
        // cut the blurred render's CPU time by about a fifth for 3 % more variance
        // (docs/scene-file.md, "Motion blur"). Where the segment is thin (kThinCell), the
        // control is 0: plain ratio tracking there.
        MediumPoint mp;
        SampledSpectrum sigmaC(0.f);
        if (sigmaMaj * (t1 - t0) >= kThinCell) {
            m.evalStill(r.at(0.5f * (t0 + t1)), mc, &mp);
            ++ctx.lookups;
            sigmaC = mp.sigmaA + mp.sigmaS;
        }
        float sigmaR = 0.f;
        for (int k = 0; k < kSpectrumSamples; ++k) {
            sigmaC[k] = clamp(sigmaC[k], 0.f, sigmaMaj);
            sigmaR = std::max(sigmaR, std::max(sigmaMaj - sigmaC[k], sigmaC[k]));
        }
        T *= exp(sigmaC * -(t1 - t0));
        // The residual σt − σc by ratio tracking at rate σ̄r ≥ max(σ̄ − σc, σc): each factor
        // 1 − (σt − σc)/σ̄r lies in [0, 2], close to 1 where σt stays near its control.
        for (float t = t0;;) {
            const float need = tau / sigmaR;
            if (!(t + need < t1)) {
                tau -= sigmaR * (t1 - t);
                return true;
            }
            t += need;
            tau = exponentialDraw(sampler);
            if (++collisions >= ctx.maxCollisions) {
                capped = true;
                return false;
            }
            m.eval(r.at(t), mc, &mp);
            ++ctx.lookups;
            T *= SampledSpectrum(1.f) - (mp.sigmaA + mp.sigmaS - sigmaC) / sigmaR;
            if (!russianRoulette(&T, sampler)) return false;
        }
    });
    if (capped) {
        // A flight cut at the collision cap has an unfinished estimate: treated as opaque.
        ++ctx.cappedFlights;
        return SampledSpectrum(0.f);
    }
    return T;
}

}  // namespace mirage
