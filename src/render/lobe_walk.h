// Lobe walks of the path tracer (render/volpath.cpp), drawn from the lobes about the lights
// (render/light_lobes.h). In a strongly forward medium under a light, the
// light a medium vertex receives after more scatterings comes mostly along the light's
// beam: the next vertices' phase functions score up to p(0) there (26/sr for sea water's
// particles), and a path that turns up the beam meets several such vertices in a row. The
// path's phase samples, drawn about its own direction, find the beam rarely and brightly.
// So each medium vertex x_i also starts a walk whose first direction is drawn from the
// lobes about the lights and whose next ones from the phase function, going on past each
// of its real collisions with probability q (kLobeWalkGoesOn), scoring next-event
// estimates on the way; it ends at a surface, at an absorption, outside the media. Its
// vertices leave the lights at infinity to its continuation as the path's do, the escape
// counting 1/q of itself: on the sky-hdr regime (a cloud under a map with a sun,
// docs/regimes.md; 64 samples, two seeds, relMSE × CPU seconds) 1.07 against 1.60 with a
// second shadow ray of their own, whose phase sample the continuation's duplicated.
//
// A next-event estimate at the k-th vertex of a run of medium vertices can then come from
// the path itself or from the walk started at any earlier vertex j of the run. Their
// densities differ in one direction and in the q's, so the balance heuristic (Veach 1997,
// §9.2) weighs every one of them by
//     1 / (1 + Σ_j s r_j q^(k−1−j)),  r_j = pdf_lobes(ω_j) / pdf_phase(ω_j),
// on the directions the estimate's own path took, with its throughput taken as if every
// direction had been drawn from the phase function (p/pdf_phase), and s the probability
// that a medium vertex starts a walk (render/light_lobes.h: lobeWalkStart; 1 but in media
// of albedo above 0.96, whose paths are long). The sum is kept along the path
// (CameraPath::lobeRatios: S ← q S + s r at each medium vertex, + r at a diffuse one). No walk
// crosses a surface or a re-emission, so the sum restarts there; a diffuse surface starts a
// walk of its own, the BSDF in the phase function's place, and its r begins the next run (the
// sand under a sunlit sea, the walls of a lit water box). Weights never exceed one, and the
// path's own throughput is untouched, so the long paths of a dense sea gain no product of
// weights (a one-sample mixture of phase and lobes at each vertex, weighing p / (½ p + ½
// pdf_lobes), up to 2, made bright outliers in green water).
//
// Measured on the gallery's underwater scene (24×16 pixels, 1024 samples, relMSE against
// 4× the samples): 0.26 with guided surface continuations alone, 0.020 with walks from
// medium vertices (q = 0.75; 0.022 at q = 0.5, 0.020 at 0.9 for more time), 0.013 with
// walks from the sand too, for 1.32× the instructions per sample (callgrind, 64 samples):
// 15× less time to the same error.
#pragma once

#include "render/camera_path.h"
#include "render/light_lobes.h"

namespace mirage {

// The probability that a lobe walk goes on past each of its vertices.
constexpr float kLobeWalkGoesOn = 0.75f;

// The walk from a medium vertex x, started with the path as it reached x (its ray, its
// throughput, the run's sum there); no vertex of it at or past maxDepth.
void walkFromMedium(const RenderScene& scene, const LightLobes& lobes, const Collision& x,
                    const CameraPath& path, int maxDepth, Sampler& sampler, ThreadState& ts,
                    const PathRecorder& rec);

// The walk from a diffuse surface vertex, where a run of medium vertices begins: the BSDF
// takes the phase function's place (f |cos| and its pdf).
void walkFromSurface(const RenderScene& scene, const LightLobes& lobes, const SurfaceHit& hit,
                     const CameraPath& path, int maxDepth, Sampler& sampler, ThreadState& ts,
                     const PathRecorder& rec);

}  // namespace mirage
