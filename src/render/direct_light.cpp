#include "render/direct_light.h"

namespace mirage {

SampledSpectrum directLightMedium(const RenderScene& scene, const Collision& c, const Vec3& wo,
                                  Sampler& sampler, ThreadState& ts) {
    SampledSpectrum L(0.f);
    const Medium& m = ts.tracking.medium(c.medium);
    for (const auto& light : scene.lights) {
        float u1 = sampler.get1D(), u2 = sampler.get1D();
        LightSample ls;
        if (!light->sampleLi(c.p, u1, u2, ts.tracking.wavelengths(), &ls)) continue;
        // The light travels along −wi into the point and leaves along wo.
        SampledSpectrum phase = m.phaseEval(c.mp, -ls.wi, wo);
        if (phase.isZero()) continue;
        Ray shadow{c.p, ls.wi, ls.distance};
        SampledSpectrum T = transmittance(ts.tracking, shadow, ls.distance, sampler);
        L += T * phase * ls.Li;
    }
    return L;
}

}  // namespace mirage
