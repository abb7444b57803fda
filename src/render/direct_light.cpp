#include "render/direct_light.h"

namespace mirage {

namespace {

// The shadow ray's length short of the light: a quad light may lie on a surface (the ceiling
// of a Cornell box), which must not occlude its own light.
float shadowLength(const Vec3& target, float distance) {
    return std::isfinite(distance) ? distance - 4.f * surfaceEpsilon(target) : distance;
}

}  // namespace

SampledSpectrum directLightMedium(const RenderScene& scene, const Collision& c, const Vec3& wo,
                                  Sampler& sampler, ThreadState& ts) {
    SampledSpectrum L(0.f);
    const Medium& m = ts.tracking.medium(c.medium);
    SampledSpectrum* split = ts.startLightSplit();
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        float u1, u2;
        sampler.get2D(&u1, &u2);  // one pair of dimensions: stratified over the light
        LightSample ls;
        if (!light->sampleLi(c.p, u1, u2, ts.tracking.wavelengths(), &ls)) continue;
        // The light travels along −wi into the point and leaves along wo.
        SampledSpectrum phase = m.phaseEval(c.mp, -ls.wi, wo);
        if (phase.isZero()) continue;
        if (scene.hasSurfaces() &&
            scene.geometry->occluded(c.p, ls.wi, shadowLength(c.p + ls.wi * ls.distance, ls.distance)))
            continue;
        Ray shadow{c.p, ls.wi, ls.distance};
        SampledSpectrum T = transmittance(ts.tracking, shadow, ls.distance, sampler);
        const SampledSpectrum term = T * phase * ls.Li;
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    return L;
}

SampledSpectrum directLightSurface(const RenderScene& scene, const SurfaceHit& hit,
                                   const Material& material, const Vec3& wo, Sampler& sampler,
                                   ThreadState& ts) {
    SampledSpectrum L(0.f);
    Frame frame(hit.ns);
    Vec3 woL = frame.toLocal(wo);
    const float side = dot(wo, hit.ng);
    SampledSpectrum* split = ts.startLightSplit();
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        float u1, u2;
        sampler.get2D(&u1, &u2);  // one pair of dimensions: stratified over the light
        LightSample ls;
        if (!light->sampleLi(hit.p, u1, u2, ts.tracking.wavelengths(), &ls)) continue;
        // Light from behind the geometric surface cannot reach the viewer's side.
        if (dot(ls.wi, hit.ng) * side <= 0.f) continue;
        Vec3 wiL = frame.toLocal(ls.wi);
        SampledSpectrum f = material.eval(woL, wiL, ts.tracking.wavelengths());
        if (f.isZero()) continue;
        Ray shadow = spawnRay(hit, ls.wi, ls.distance);
        float len = shadowLength(hit.p + ls.wi * ls.distance, ls.distance);
        if (scene.geometry->occluded(shadow.o, ls.wi, len)) continue;
        SampledSpectrum T = transmittance(ts.tracking, shadow, ls.distance, sampler);
        const SampledSpectrum term = T * f * std::abs(wiL.z) * ls.Li;
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
