// One photon's random walk through the media, one free flight at a time: the part of the
// photon pass that the slab instrument (`mirage slab`) shares, so that both measure the same
// transport code. The walk itself (what to store, where boundaries are, when to stop) belongs
// to the caller.
//
// A flight is delta tracking (transport/tracking.h) with the albedo roulette of Jensen &
// Christensen (1998) at each tentative collision: absorption with probability σa/σ̄, real
// scattering with σs/σ̄, otherwise a null collision and the flight goes on. The roulette makes
// the three events' weights σ/(σ̄ P) equal to 1, so a photon's power never changes at a
// collision, and photons of equal power stay of equal power (the best case for a density
// estimate). Photons are monochromatic: the tracking context's four wavelengths are all the
// photon's, so the event probabilities (means over wavelengths) are those at its wavelength.
#pragma once

#include <vector>

#include "core/rng.h"
#include "transport/curved_tracking.h"
#include "transport/tracking.h"

namespace mirage {

enum class FlightEnd {
    Escaped,  // no real collision before tMax: the photon left every medium (tMax = ∞)
    Absorbed,
    Scattered,
    // Absorbed by a fluorescent component and re-emitted (the Γ roulette, transport/
    // reemission.h): the photon goes on along wo at the walk's new wavelength() with its power
    // times `weight` = λi/λo. A caller that does not handle it may treat it as Absorbed.
    Reemitted,
};

struct FlightEvent {
    FlightEnd end;
    Vec3 p;              // world position of the absorption or scattering (m)
    Vec3 wi;             // direction of the flight
    Vec3 wo;             // Scattered: new direction, sampled from the phase function
    float weight = 1.f;  // Scattered: phase weight p/pdf at the photon's wavelength; 1 for a
                         // single lobe, which is sampled exactly. Reemitted: λi/λo
    float lambdaIn = 0.f, lambdaOut = 0.f;  // Reemitted: absorbed and re-emitted λ (nm)
};

class PhotonWalk {
public:
    explicit PhotonWalk(const std::vector<const Medium*>& media);

    // The photon's wavelength (nm); call before its first flight.
    void setWavelength(float lambdaNm);
    float wavelength() const { return mLambda; }

    // One free flight along ray (unit direction) over (0, tMax).
    FlightEvent fly(const Ray& ray, float tMax, Sampler& sampler);

    // One free flight along the curved (Fermat) path of `walk` from start's origin along its
    // unit direction, on the photon's wavelength's path (transport/curved_tracking.h): optical
    // depth over arc length, each chord tested by the walk's surfaces. The events are those of
    // fly(); wi is the direction of the chord the event lies on (the path's tangent to within
    // the chord's turn). *end says how the walk ended: Surface (ev.end Escaped, at a surface on
    // end->chord), Reached or Capped (ev.end Escaped: the caller goes on straight from end->p
    // along end->direction).
    FlightEvent flyCurved(const CurvedWalk& walk, const Ray& start, Sampler& sampler,
                          CurvedWalkEnd* end);

    TrackingContext& tracking() { return mTracking; }
    float timeOffset() const { return mTracking.timeOffset(); }

private:
    // The albedo and Γ roulettes at a tentative collision met flying along dir.
    Track collide(const Collision& c, const Vec3& dir, Sampler& sampler, FlightEvent* ev);

    TrackingContext mTracking;
    float mLambda = 0.f;
};

}  // namespace mirage
