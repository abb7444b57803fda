#include "render/direct_light.h"

#include "light/surface_light.h"
#include "render/lamp_sampling.h"

namespace mirage {

namespace {

// The shadow ray's length short of the light: a quad light may lie on a surface (the ceiling
// of a Cornell box), which must not occlude its own light.
float shadowLength(const Vec3& target, float distance) {
    return std::isfinite(distance) ? distance - 4.f * surfaceEpsilon(target) : distance;
}

// Power heuristic (Veach 1997, §9.2.1, β = 2): the weight of a strategy with pdf `a` against
// one with pdf `b` for the same direction.
float powerHeuristic(float a, float b) {
    const float a2 = a * a, b2 = a2 + b * b;
    return b2 > 0.f ? a2 / b2 : 0.f;
}

// Whether the ray from o along the unit wi meets light `i` (then *out holds the distance, the
// radiance and the pdf its sampleLi draws wi with): Light::hitLi, but for the emissive
// surfaces, which only the geometry can intersect — the first surface along wi, if it is one of
// their emitters.
bool hitLight(const RenderScene& scene, const Light& light, const Vec3& o, const Vec3& wi,
              const SampledWavelengths& w, LightSample* out) {
    const SurfaceLight* surfaces = surfaceLightOf(light);
    if (!surfaces) return light.hitLi(o, wi, w, out);
    const std::optional<SurfaceHit> hit = scene.geometry->intersect(Ray{o, wi, kInfinity});
    if (!hit || !surfaces->samples(hit->shape)) return false;
    out->wi = wi;
    out->distance = hit->t;
    out->Li = scene.geometry->materialAt(*hit).emission(w);
    out->pdf = surfaces->pdfAt(hit->material, o, hit->p, hit->ng);
    return out->pdf > 0.f;
}

}  // namespace

// Light arriving at a medium point, by next-event estimation. A light a direction can hit (the
// quad, the dome, the emissive surfaces) is sampled twice, by the light and by the phase function,
// the two combined by multiple importance sampling (Veach 1997): in a strongly forward medium
// (marine particles, HG g = 0.92, p up to 26/sr against a mean of 1/4π) the light's own samples
// alone score rare directions along the lobe ~300 times the mean, the speckles of a lit water box;
// phase samples take those directions at the lobe's own density. Both are shadow rays with the same
// transmittance estimate, so the sum stays an unbiased estimate of ∫ T p L dω.
SampledSpectrum directLightMedium(const RenderScene& scene, const Collision& c, const Vec3& wo,
                                  Sampler& sampler, ThreadState& ts, const LampSampling* lamps,
                                  bool infiniteOnly) {
    SampledSpectrum L(0.f);
    const Medium& m = ts.tracking.medium(c.medium);
    const SampledWavelengths& w = ts.tracking.wavelengths();
    SampledSpectrum* split = ts.startLightSplit();
    // One shadow ray's transmittance times the radiance it carries; 0 when blocked.
    auto shadowed = [&](const LightSample& ls) {
        if (scene.hasSurfaces() &&
            scene.geometry->occluded(c.p, ls.wi,
                                     shadowLength(c.p + ls.wi * ls.distance, ls.distance)))
            return SampledSpectrum(0.f);
        Ray shadow{c.p, ls.wi, ls.distance};
        return transmittance(ts.tracking, shadow, ls.distance, sampler) * ls.Li;
    };
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        if (infiniteOnly && !light->infinite()) continue;
        const float share = lamps ? lamps->scatterPointWeight(i, c) : 1.f;
        if (!(share > 0.f)) continue;
        float u1, u2;
        sampler.get2D(&u1, &u2);  // one pair of dimensions: stratified over the light
        SampledSpectrum term(0.f);
        LightSample ls;
        if (light->sampleLi(c.p, u1, u2, w, &ls)) {
            // The light travels along −wi into the point and leaves along wo.
            const SampledSpectrum phase = m.phaseEval(c.mp, -ls.wi, wo);
            const float mis =
                ls.pdf > 0.f ? powerHeuristic(ls.pdf, m.phasePdf(c.mp, -wo, ls.wi)) : share;
            if (!phase.isZero() && mis > 0.f) term += shadowed(ls) * phase * mis;
        }
        if (ls.pdf > 0.f) {
            // The phase function's sample, for a light a direction can hit (its samples have a pdf)
            // that the point sees the emitting side of.
            SampledSpectrum weight;
            float pdf;
            const float uc = sampler.get1D(), v1 = sampler.get1D(), v2 = sampler.get1D();
            const Vec3 wi = m.phaseSample(c.mp, -wo, uc, v1, v2, &weight, &pdf);
            LightSample hs;
            if (pdf > 0.f && hitLight(scene, *light, c.p, wi, w, &hs))
                term += shadowed(hs) * weight * powerHeuristic(pdf, hs.pdf);
            term *= share;
        }
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    return L;
}

// Light arriving at a diffuse surface point, by next-event estimation. A light at infinity (the
// dome) is sampled twice, by the light and by the BSDF, combined by multiple importance sampling
// as in a medium: a constant dome drawn uniformly over the sphere sends half its samples below
// the surface, and the BSDF's cosine lobe draws exactly the directions that count. So are the
// emissive surfaces, which may be large and near (a glowing wall beside the point), where
// points drawn on them by area score d²/cos without bound. A quad's small solid angle would
// waste most BSDF samples, so it keeps its own sampling alone.
SampledSpectrum directLightSurface(const RenderScene& scene, const SurfaceHit& hit,
                                   const Material& material, const Vec3& wo, Sampler& sampler,
                                   ThreadState& ts) {
    SampledSpectrum L(0.f);
    const SampledWavelengths& w = ts.tracking.wavelengths();
    Frame frame(hit.ns);
    Vec3 woL = frame.toLocal(wo);
    const float side = dot(wo, hit.ng);
    SampledSpectrum* split = ts.startLightSplit();
    // T f |cos θi| for a direction towards the light (Li left to the caller); 0 when the light
    // is behind the surface, or blocked.
    auto shadowed = [&](const LightSample& ls) {
        // Light from behind the geometric surface cannot reach the viewer's side.
        if (dot(ls.wi, hit.ng) * side <= 0.f) return SampledSpectrum(0.f);
        const Vec3 wiL = frame.toLocal(ls.wi);
        const SampledSpectrum f = material.eval(woL, wiL, w);
        if (f.isZero()) return SampledSpectrum(0.f);
        Ray shadow = spawnRay(hit, ls.wi, ls.distance);
        float len = shadowLength(hit.p + ls.wi * ls.distance, ls.distance);
        if (scene.geometry->occluded(shadow.o, ls.wi, len)) return SampledSpectrum(0.f);
        return transmittance(ts.tracking, shadow, ls.distance, sampler) * f * std::abs(wiL.z);
    };
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        const bool twoStrategies = light->infinite() || surfaceLightOf(*light);
        float u1, u2;
        sampler.get2D(&u1, &u2);  // one pair of dimensions: stratified over the light
        SampledSpectrum term(0.f);
        LightSample ls;
        if (light->sampleLi(hit.p, u1, u2, w, &ls)) {
            const float mis = twoStrategies && ls.pdf > 0.f
                                  ? powerHeuristic(ls.pdf, material.pdf(woL, frame.toLocal(ls.wi)))
                                  : 1.f;
            term += shadowed(ls) * ls.Li * mis;
        }
        if (twoStrategies) {
            const float uc = sampler.get1D(), v1 = sampler.get1D(), v2 = sampler.get1D();
            BsdfSample bs;
            LightSample hs;
            if (material.sample(woL, uc, v1, v2, w, TransportMode::Radiance, &bs) && !bs.specular) {
                const float pdf = material.pdf(woL, bs.wi);
                const Vec3 wi = frame.toWorld(bs.wi);
                if (pdf > 0.f && hitLight(scene, *light, spawnRay(hit, wi).o, wi, w, &hs))
                    term += shadowed(hs) * hs.Li * (powerHeuristic(pdf, hs.pdf) / pdf);
            }
        }
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    return L;
}

SampledSpectrum escapedRadiance(const RenderScene& scene, const Vec3& d,
                                const SampledWavelengths& w, bool cameraRay) {
    SampledSpectrum L(0.f);
    for (const auto& light : scene.lights)
        if (light->infinite()) L += light->escapedRadiance(d, w, cameraRay);
    return L;
}

}  // namespace mirage
