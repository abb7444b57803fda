// The direction a camera path continues in after a diffuse surface, guided towards the lights
// in scenes with strongly forward media (sea water's particles, HG g 0.92: p(0) = 26/sr
// against a mean of 1/4π).
//
// Why. A medium vertex's next-event estimate scores p(θ) of the angle between the path's last
// segment and the light. In such a medium the light seen just past the forward lobe — an
// aureole about a lamp, a glow about the sun's beam — is bright and narrow, and a path leaving
// a wall or the sand finds it only when its cosine sample happens to point at the light: rare,
// bright samples, the speckles of the Cornell-water scenes. Here the next direction is drawn,
// with probability ½, from an HG lobe (g 0.9) about the direction of a light instead (one light
// at random among those not at infinity, its direction that of its sample for (½, ½): a distant
// light's, a point's, about a quad's middle), else from the BSDF, and weighted by
// f |cos| / (½ pdf_bsdf + ½ mean pdf_lobes) — one-sample multiple importance sampling with
// the balance heuristic (Veach 1997, §9.2.4), unbiased since the BSDF covers every direction
// that reflects, and at most 2ρ.
// Medium vertices keep plain phase sampling: the same mixture with the phase lobe turned
// towards the light halved underwater.toml's relMSE but made bright outliers in the greener
// water of underwater_green.toml (not understood yet), so it is left out.
// Not used (plain sampling, the same random numbers as before) where no medium of the scene
// peaks above 5/sr (HG g ≳ 0.82): smoke, fog and clouds keep their paths.
#pragma once

#include "geometry/geometry_scene.h"
#include "render/integrator.h"
#include "transport/path_vertex.h"

namespace mirage {

// Whether any medium of the scene is forward enough for guiding, and a light to guide to.
bool guidesPaths(const RenderScene& scene);

// The next ray at a diffuse surface hit, the path arriving along dir (as continueAtSurface:
// false when the path ends; β times f |cos| / pdf).
bool continueAtDiffuse(const RenderScene& scene, const Material& material, const SurfaceHit& hit,
                       const Vec3& dir, const SampledWavelengths& w, Sampler& sampler,
                       PathThroughput* path, Ray* next);

}  // namespace mirage
