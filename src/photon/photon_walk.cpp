#include "photon/photon_walk.h"

#include "transport/reemission.h"

namespace mirage {

PhotonWalk::PhotonWalk(const std::vector<const Medium*>& media) : mTracking(media) {}

void PhotonWalk::setWavelength(float lambdaNm) {
    mLambda = lambdaNm;
    SampledWavelengths w;
    w.lambda.fill(lambdaNm);
    // The pdf of the wavelength never enters a photon's weight: the light drew λ ∝ its
    // spectral power, and the photon's power Φ/N already accounts for it.
    w.pdf.fill(1.f);
    mTracking.setWavelengths(w);
}

Track PhotonWalk::collide(const Collision& c, const Vec3& dir, Sampler& sampler, FlightEvent* ev) {
    // All four wavelengths are the photon's, so the means eventProbabilities takes are
    // the probabilities at index 0: P_a = σa(λ)/σ̄, P_s = σs(λ)/σ̄, P_n = σn(λ)/σ̄.
    EventProbabilities e = eventProbabilities(c);
    float u = sampler.get1D();
    if (u < e.pAbsorb) {
        ev->end = FlightEnd::Absorbed;
        ev->p = c.p;
        // The second roulette (Gutierrez et al. 2005): re-emission with the quantum
        // efficiency of the absorbing component. It draws nothing in media without one.
        const Medium& m = mTracking.medium(size_t(c.medium));
        Reemission r;
        if (sampleReemission(m, mTracking.context(size_t(c.medium)), c.p, mLambda, sampler, &r)) {
            ev->end = FlightEnd::Reemitted;
            ev->wo = r.wo;
            ev->weight = r.powerScale;
            ev->lambdaIn = mLambda;
            ev->lambdaOut = r.lambdaNm;
        }
        return Track::Stop;
    }
    if (u < e.pAbsorb + e.pScatter) {
        ev->end = FlightEnd::Scattered;
        ev->p = c.p;
        ev->wi = dir;
        const Medium& m = mTracking.medium(size_t(c.medium));
        SampledSpectrum weight;
        float pdf;
        float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        ev->wo = m.phaseSample(c.mp, dir, uc, u1, u2, &weight, &pdf);
        ev->weight = weight[0];
        return Track::Stop;
    }
    return Track::Continue;
}

FlightEvent PhotonWalk::fly(const Ray& ray, float tMax, Sampler& sampler) {
    FlightEvent ev;
    ev.end = FlightEnd::Escaped;
    ev.p = ray.o;
    ev.wi = ray.d;
    const uint64_t capped = mTracking.cappedFlights;
    trackCollisions(mTracking, ray, tMax, sampler,
                    [&](const Collision& c) { return collide(c, ray.d, sampler, &ev); });
    // A flight cut at the collision cap ends the photon where it stands (counted by the caller
    // through tracking().cappedFlights).
    if (mTracking.cappedFlights != capped) ev.end = FlightEnd::Absorbed;
    // The new wavelength, once tracking no longer uses the contexts' old one.
    if (ev.end == FlightEnd::Reemitted) setWavelength(ev.lambdaOut);
    return ev;
}

FlightEvent PhotonWalk::flyCurved(const CurvedWalk& walk, const Ray& start, Sampler& sampler,
                                  CurvedWalkEnd* end) {
    FlightEvent ev;
    ev.end = FlightEnd::Escaped;
    ev.p = start.o;
    ev.wi = start.d;
    // Every chord is handed to the surface test before it is tracked: that is where the
    // direction of the chord the collisions lie on is known.
    Vec3 chordDir = start.d;
    const CurvedWalk chords{walk.field, walk.settings, walk.maxArc,
                            [&](const Ray& chord, float tMax) {
                                chordDir = chord.d;
                                return walk.surfaces ? walk.surfaces(chord, tMax) : kInfinity;
                            }};
    const uint64_t capped = mTracking.cappedFlights;
    *end = trackCurvedCollisions(
        mTracking, chords, start, mLambda, sampler,
        [&](const Collision& c, float) { return collide(c, chordDir, sampler, &ev); });
    if (mTracking.cappedFlights != capped) ev.end = FlightEnd::Absorbed;  // as in fly()
    if (ev.end == FlightEnd::Escaped) ev.wi = end->direction;
    if (ev.end == FlightEnd::Reemitted) setWavelength(ev.lambdaOut);
    return ev;
}

}  // namespace mirage
