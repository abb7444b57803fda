#include "render/line_emission.h"

#include <array>

#include "render/camera_path.h"
#include "render/direct_light.h"

namespace mirage {

float flightEmissionWeight(const EmissionLight& light, const Vec3& x, const Vec3& dir,
                           float phasePdf, TrackingContext& tracking) {
    return powerHeuristic(phasePdf, light.pdf(x, dir, tracking));
}

void sampleLineEmission(const RenderScene& scene, const EmissionLight& light, const Collision& x,
                        const Vec3& dirIn, const SampledSpectrum& beta, bool alone,
                        Sampler& sampler, ThreadState& ts, PathRecorder& rec) {
    Vec3 wi;
    float pdfLine;
    if (!light.sample(x.p, ts.tracking, sampler, &wi, &pdfLine)) return;
    const Medium& m = ts.tracking.medium(x.medium);
    const SampledSpectrum phase = m.phaseEval(x.mp, dirIn, wi);
    if (phase.isZero()) return;
    const float w = alone ? 1.f : powerHeuristic(pdfLine, m.phasePdf(x.mp, dirIn, wi));
    if (!(w > 0.f)) return;
    const Ray ray{x.p, wi, kInfinity};
    recordLineEmission(light, ts.tracking, ray, surfaceAhead(scene, ray).tEnd,
                       beta * phase * (w / pdfLine), sampler, rec);
}

SampledSpectrum recordLineEmission(const EmissionLight& light, TrackingContext& tracking,
                                   const Ray& ray, float tEnd, const SampledSpectrum& scale,
                                   Sampler& sampler, PathRecorder& rec) {
    SampledSpectrum sum(0.f);
    EmissionLight::LinePoint point;
    if (!light.sampleDistance(ray, tEnd, tracking, sampler.get1D(), true, &point)) return sum;
    const float t = point.t, pdf = point.pdf;
    // The emission at t first: where it is 0 (the floor's points), no transmittance is tracked.
    std::array<MediumPoint, kMaxEmissiveMedia> at;
    size_t glowing = 0;
    for (size_t i = 0; i < tracking.size(); ++i) {
        const Medium& m = tracking.medium(i);
        if (!m.emissive()) continue;
        Medium::Context& ctx = tracking.context(i);
        m.eval(ctx.toObject(ray).at(t), ctx, &at[glowing]);
        ++tracking.lookups;
        if (!(at[glowing].sigmaA * at[glowing].Le).isZero()) ++glowing;
    }
    if (glowing == 0) return sum;
    const SampledSpectrum T = transmittance(tracking, Ray{ray.o, ray.d, t}, t, sampler) * scale;
    for (size_t k = 0; k < glowing && !T.isZero(); ++k) {
        const SampledSpectrum term = T * at[k].sigmaA * at[k].Le / pdf;
        rec.emittedInMedium(term, t, at[k].temperature);
        sum += term;
    }
    return sum;
}

}  // namespace mirage
