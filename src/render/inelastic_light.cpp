#include "render/inelastic_light.h"

#include <cmath>

namespace mirage {

SampledSpectrum directLightIsotropic(const RenderScene& scene, const Vec3& p, Sampler& sampler,
                                     ThreadState& ts) {
    SampledSpectrum L(0.f);
    SampledSpectrum* split = ts.startLightSplit();
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        float u1 = sampler.get1D(), u2 = sampler.get1D();
        LightSample ls;
        if (!light->sampleLi(p, u1, u2, ts.tracking.wavelengths(), &ls)) continue;
        // Short of the light itself, as direct_light.cpp: a quad light on a surface must not
        // occlude its own light.
        Vec3 target = p + ls.wi * ls.distance;
        float length = std::isfinite(ls.distance)
                           ? ls.distance - 4.f * surfaceEpsilon(target)
                           : ls.distance;
        if (scene.hasSurfaces() && scene.geometry->occluded(p, ls.wi, length)) continue;
        Ray shadow{p, ls.wi, ls.distance};
        const SampledSpectrum term =
            transmittance(ts.tracking, shadow, ls.distance, sampler) * ls.Li * kInv4Pi;
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    return L;
}

}  // namespace mirage
