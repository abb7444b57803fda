// Next-event estimation shared by every integrator: each light is sampled once and its
// contribution is attenuated by a ratio-tracked shadow ray. Surfaces block shadow rays (an
// Embree occlusion test first, which is far cheaper than tracking); glass blocks them too, since
// light through specular surfaces is not reachable by a shadow ray (photons carry caustics).
// Where a [refraction] field bends light (ThreadState::curved), shadow rays towards lights at
// infinity follow Fermat paths to where they leave the scene; direct_light.cpp says how, and
// why lamps at a finite distance keep straight ones.
#pragma once

#include "render/integrator.h"

namespace mirage {

class LampSampling;
class SunShade;

// What a medium point's estimate covers.
enum class MediumLights {
    All,           // every light, by all of its strategies
    InfiniteOnly,  // the lights at infinity alone (the estimate at a point drawn for them)
    // Every light, but the lights at infinity leave their phase-function strategy to the path's
    // own continuation: skyAtEscape scores them where it leaves the scene (direct_light.cpp).
    SkyByEscape,
};

// Power heuristic (Veach 1997, §9.2.1, β = 2): the weight of a strategy with pdf `a` against
// one with pdf `b` for the same direction.
inline float powerHeuristic(float a, float b) {
    const float a2 = a * a, b2 = a2 + b * b;
    return b2 > 0.f ? a2 / b2 : 0.f;
}

// Where a path's medium vertices leave the lights at infinity to their escapes
// (MediumLights::SkyByEscape), whether a vertex also draws those lights' own samples: with
// probability `rate`: under a sky with a sun, SunShade::drawRate at the vertex; else 1 unless the
// last sample the path drew found no light (`dark`), then kDarkSkyRate (direct_light.cpp says
// why). The path keeps `dark` from vertex to vertex; the vertex's rate weighs its escape
// (skyAtEscape).
struct SkyDraws {
    bool dark = false;  // in: the path's last drawn sample found no light; out: this vertex's
    // in: where the scene's sun is hidden (render/sun_shade.h), which then sets the rate by the
    // vertex's position instead of `dark`; null where the scene has none.
    const SunShade* shade = nullptr;
    float rate = 1.f;  // out: the probability this vertex drew them with
};

// Σ_lights p(−wi, wo) · Li · T(shadow ray). wo is the direction the light leaves towards the
// viewer (the reverse of the incoming path direction). With `lamps`, the segment c lies on
// draws points towards the point and spot lights and the lights at infinity too
// (render/lamp_sampling.h), and each light's term here carries its weight against them (a
// light of weight 0 draws no shadow ray). With `sky` (SkyByEscape only), the lights at
// infinity are drawn at its rate.
SampledSpectrum directLightMedium(const RenderScene& scene, const Collision& c, const Vec3& wo,
                                  Sampler& sampler, ThreadState& ts,
                                  const LampSampling* lamps = nullptr,
                                  MediumLights which = MediumLights::All,
                                  SkyDraws* sky = nullptr);

// The lights at infinity seen by a path's continuation that left the scene along `ray` after a
// medium point estimated with MediumLights::SkyByEscape, which drew the ray's direction with
// density phasePdf and the lights' own samples at `skyRate` (SkyDraws): the phase function's
// strategy of those lights, weighed against their own samples by the power heuristic, and its
// split by light group in ts.lightSplit.
SampledSpectrum skyAtEscape(const RenderScene& scene, const Ray& ray, float phasePdf,
                            float skyRate, const SampledWavelengths& w, ThreadState& ts);

// Σ_lights f(wo, wi) |cos θi| · Li · T(shadow ray) at a diffuse surface point; wo (world, unit)
// points towards the viewer. Light arriving from the other side of the surface than wo is not
// counted (Lambertian surfaces here are two-sided but opaque).
SampledSpectrum directLightSurface(const RenderScene& scene, const SurfaceHit& hit,
                                   const Material& material, const Vec3& wo, Sampler& sampler,
                                   ThreadState& ts);

// Σ_lights of the radiance along d of a ray that leaves the scene (lights at infinity: the dome).
// Integrators add it only where no next-event estimate has counted that light already: on the
// camera ray (cameraRay true) and after mirrors and glass, which shadow rays cannot cross.
SampledSpectrum escapedRadiance(const RenderScene& scene, const Vec3& d,
                                const SampledWavelengths& w, bool cameraRay);

}  // namespace mirage
