// Connections from a point to the lights at infinity (the dome, distant lights) along Fermat
// paths (Gutierrez et al. 2005: light follows curved paths where the refractive index varies).
// A straight shadow ray started towards such a light does not reach it where the index varies:
// the path bends and leaves the scene in another direction. Two connections are exact:
//   - escape: the path from x along a direction ωi, followed to where it leaves the scene, sees
//     the light at infinity in its escape direction ωe. The light's radiance there, by the n²
//     law L/n² = const, is L(ωe)·(n(x)/n(exit))² at x: an estimator of ∫ f(ωi) L_x(ωi) dωi for
//     any density of ωi that covers the integrand (render/curved_shadow.h weighs two of them);
//   - aim: a delta light at infinity (a sun of irradiance E along s) reaches x only along the
//     initial direction ωi* whose path leaves along s. ∫ f(ωi) E δ(ωe(ωi) − s) dωi
//     = f(ωi*) E / |dωe/dωi| at ωi*: the path is found by Newton's method on ωe(ωi) = s, with
//     the Jacobian dωe/dωi by finite differences of the escape direction, and its determinant
//     is the spread that divides the irradiance (a focusing field concentrates the sun's light,
//     a defocusing one spreads it). One root is found, from the straight direction: where a
//     strong layer images the light several times (a mirage of the sun), the others are lost.
// Where the scene ends: the photon pass emits the light of domes and distant lights from the
// scene's bounding sphere (light/light.h, light/dome_light.h) and bends photons from there on,
// so a connection bends inside that sphere and is straight beyond it, which makes the two
// passes' light the same. A path also goes straight on after the field's curved length
// (CurvedWalk::maxArc), as camera rays do (render/curved_camera.h).
#pragma once

#include <optional>

#include "transport/curved_tracking.h"

namespace mirage {

// Where a curved path from a point left the scene: its direction there and the index at its
// ends (on the path's wavelength), and the transmittance along it where it was tracked.
struct CurvedEscape {
    Vec3 direction;       // unit, the escape direction ωe
    double nStart = 1.0;  // n at the path's start
    double nExit = 1.0;   // n where it left the sphere, or went straight on
    SampledSpectrum T{1.f};
    // The radiance factor from the exit to the start (the n² law).
    float radianceScale() const { return radianceIndexScale(nExit, nStart); }
};

// The curved path of `walk` from start.o along the unit start.d to where it leaves the walk's
// bounds (the scene's sphere), then straight on. Nothing when a surface of the walk blocks it. With
// ctx and sampler the transmittance is ratio-tracked along it (chord by chord, as
// curvedTransmittance); without, only the geometry is followed (T stays 1).
std::optional<CurvedEscape> escapeCurved(const CurvedWalk& walk, const Ray& start, float lambdaNm,
                                         TrackingContext* ctx = nullptr,
                                         Sampler* sampler = nullptr);

// The path towards a delta light at infinity: the initial direction whose path leaves along the
// unit `target`, the path's transmittance and index factor (escape), and the solid-angle ratio
// |dωe/dωi| there (spread). Nothing when no path is found (blocked, or Newton's method does not
// converge within its iterations: no light arrives along the one root sought).
struct CurvedAim {
    Vec3 wi;
    CurvedEscape escape;
    float spread = 1.f;
};
std::optional<CurvedAim> aimCurved(const CurvedWalk& walk, const Vec3& origin, const Vec3& target,
                                   float lambdaNm, TrackingContext& ctx, Sampler& sampler);

}  // namespace mirage
