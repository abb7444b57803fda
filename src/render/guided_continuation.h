// The direction a camera path continues in after a scattering event, guided towards the lights
// in scenes with strongly forward media (sea water's particles, HG g 0.92: p(0) = 26/sr
// against a mean of 1/4π).
//
// Why. A vertex's next-event estimate scores p(θ) of the angle between the path's last segment
// and the light. In such a medium the light seen just past the forward lobe — a glow about the
// sun's beam, an aureole about a lamp — is bright and narrow, and a path finds it only when
// the previous vertex (a sand floor, a wall, another particle) happened to send it up the beam:
// rare, bright samples, the speckles of the underwater and Cornell-water scenes. Here the next
// direction is drawn, with probability ½, from a lobe about the direction of a light instead
// (one light at random among those not at infinity, its direction that of its sample for
// (½, ½): a distant light's, a point's, about a quad's middle), else from the vertex's own
// lobe, and weighted by f / (½ pdf_own + ½ mean pdf_lights) — one-sample multiple importance
// sampling with the balance heuristic (Veach 1997, §9.2.4), unbiased for every direction
// either lobe can draw since the own lobe covers all of them.
// The light lobes: at a medium vertex the medium's own phase function about the light's
// direction (then own × next lobe / mixture stays below twice the smaller of the two), at a
// diffuse surface an HG lobe of g 0.9.
// Not used (plain sampling, the same random numbers as before) where no medium of the scene
// peaks above 5/sr (HG g ≳ 0.82): smoke, fog and clouds keep their paths.
#pragma once

#include "geometry/geometry_scene.h"
#include "render/integrator.h"
#include "transport/path_vertex.h"

namespace mirage {

// Whether any medium of the scene is forward enough for guiding, and a light to guide to.
bool guidesPaths(const RenderScene& scene);

// The next direction at a real scattering event in medium m at c, the path arriving along dir;
// β times f/pdf.
Vec3 continueInMedium(const RenderScene& scene, bool guided, const Medium& m, const Collision& c,
                      const Vec3& dir, const SampledWavelengths& w, Sampler& sampler,
                      PathThroughput* path);

// The next ray at a diffuse surface hit, the path arriving along dir (as continueAtSurface:
// false when the path ends; β times f |cos| / pdf).
bool continueAtDiffuse(const RenderScene& scene, const Material& material, const SurfaceHit& hit,
                       const Vec3& dir, const SampledWavelengths& w, Sampler& sampler,
                       PathThroughput* path, Ray* next);

}  // namespace mirage
