// Next-event estimation towards emissive media by line integration (Simon, Hanika, Zirr &
// Dachsbacher 2017, "Line Integration for Rendering Heterogeneous Emissive Volumes", EGSR):
// `volpath`'s light from fire at its scattering vertices.
//
// Without it, a vertex x in the smoke finds the flames' light only where its path's next
// flight happens to cross them: the flight scores β σa Le / σ̄ at its every tentative collision
// (volpath.cpp), whose expectation along the phase-sampled direction ω is
//     L_line(ω) = ∫_0^{t_s} T(x, x + tω) σa(x + tω) Le(x + tω) dt,
// t_s the nearest surface (or where the ray leaves the media). Smoke lit by a small, bright
// flame then speckles: few directions cross it. Line integration samples ω towards the
// emission instead (render/emission_light.h: ∝ the power of a coarse grid's cells, density
// p_L(ω)) and estimates the whole line at once, by one point t drawn along it ∝ the same
// grid's power per volume (EmissionLight::sampleDistance, density p_t):
//     L̂_line = T̂(x, x + tω) σa(t) Le(t) / p_t(t),
// T̂ by residual ratio tracking (transport/tracking.h), σa Le exact at t, summed over the
// emissive media there. Ratio tracking's emission at every tentative collision, the flight's
// own estimator, was tried first: where the majorant is tight (σ̄ = σt in dense, even smoke)
// its factors 1 − σt/σ̄ vanish at the first collision, and the line's estimate is one point
// drawn ∝ σt T, found in a small flame as rarely as by the flight itself: its seed noise was
// 12× the point's (tests/physics/line_emission_test.cpp's fire, 32 samples; 24.9 against
// 2.0), and only 10× below the flights' alone on the fire regime, against 23×.
//
// Two strategies for one integral, ∫ p(ω_in → ω) L_line(ω) dω, combined by the power heuristic
// (Veach 1997, §9.2.1), p_P the phase function's density of ω:
//     line sample ω_L:   β p(ω_L) L̂_line(ω_L) w_L / p_L(ω_L),  w_L = p_L² / (p_P² + p_L²)
//     the path's flight: every emission score along ω_P times   w_P = p_P² / (p_P² + p_L²)
// p_L(ω_P) once per segment (one DDA), before the flight. w_L + w_P = 1 for every ω, and the
// phase function draws every direction, so the sum stays unbiased whatever p_L misses (p_L = 0:
// the flight keeps weight 1). At a vertex after which the path will not fly (the depth cap),
// the line sample takes weight 1.
//
// Where it applies: real scattering vertices of the path itself in a scene with an emissive
// medium, `[render] emission_sampling = "line"` (the default), on straight paths. Weight 1, and
// nothing drawn, on the camera ray, after a surface vertex, after a fluorescent re-emission
// (its isotropic lobe would take a line sample of its own at λi: left out, the flight keeps the
// light there whole), and where a [refraction] field bends paths (the flight is then a curve,
// not the line). Lobe walks (render/light_lobes.h) score no emission: the path's own flight
// scores it, so the walks leave this MIS alone. The line's term of each medium glowing at its
// point is recorded as emission seen after the vertex (PathRecorder::emittedInMedium, with the
// temperature there): the same passes, light group and exact blackbody colour as the
// flight's. Where nothing glows at the point, no transmittance is tracked.
#pragma once

#include "render/emission_light.h"
#include "render/path_recorder.h"

namespace mirage {

// w_P: the weight of the path's own flight along the unit dir that its phase function drew
// from x with density phasePdf (1/sr).
float flightEmissionWeight(const EmissionLight& light, const Vec3& x, const Vec3& dir,
                           float phasePdf, TrackingContext& tracking);

// The line sample at the real scattering vertex x of a path that arrived along dirIn with
// throughput beta: its terms recorded through rec (above). `alone`: the path ends at x.
void sampleLineEmission(const RenderScene& scene, const EmissionLight& light, const Collision& x,
                        const Vec3& dirIn, const SampledSpectrum& beta, bool alone,
                        Sampler& sampler, ThreadState& ts, PathRecorder& rec);

// The estimate L̂_line along ray (a unit direction) over (0, tEnd), each emissive medium's term
// × scale recorded as emission seen after the path's last vertex. Returns their sum.
SampledSpectrum recordLineEmission(const EmissionLight& light, TrackingContext& tracking,
                                   const Ray& ray, float tEnd, const SampledSpectrum& scale,
                                   Sampler& sampler, PathRecorder& rec);

}  // namespace mirage
