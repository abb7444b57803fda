#include "render/camera_ray_data.h"

#include <optional>

namespace mirage {

namespace {

// The visible medium whose box the ray enters first before tEnd, −1 for none.
int firstVisibleMedium(const RenderScene& scene, const Ray& ray, float tEnd) {
    int first = -1;
    float tFirst = tEnd;
    for (size_t i = 0; i < scene.media.size(); ++i) {
        float t0, t1;
        if (scene.media[i]->holdout() ||
            !scene.media[i]->worldBounds().intersect(ray.o, ray.d, 0.f, tFirst, &t0, &t1))
            continue;
        first = int(i);
        tFirst = t0;
    }
    return first;
}

}  // namespace

void cameraRayData(const RenderScene& scene, const Ray& ray, Sampler& sampler, ThreadState& ts,
                   AovSample* aov, DeepSample* deep) {
    std::optional<SurfaceHit> hit;
    if (scene.hasSurfaces()) hit = scene.geometry->intersect(ray);
    const float tEnd = hit ? hit->t : ray.tMax;
    SampledSpectrum T(1.f), albedo(0.f);
    const bool crypto = aov && !aov->volumeCoverage.empty();
    float depth = kInfinity;
    const bool reached = trackCollisions(ts.tracking, ray, tEnd, sampler, [&](const Collision& c) {
        const bool visible = !ts.tracking.medium(size_t(c.medium)).holdout();
        if (visible) albedo += T * c.mp.sigmaS / c.sigmaMaj;
        const float before = T.average();
        T *= (SampledSpectrum(c.sigmaMaj) - c.mp.sigmaA - c.mp.sigmaS) / c.sigmaMaj;
        if (!(depth < kInfinity) && T.average() <= 0.5f) depth = c.t;
        // The coverage this collision adds (before the roulette rescales T), to the deep
        // samples and to the medium's Cryptomatte coverage.
        if (deep && visible) deep->coverage.push_back({{c.t, false}, before - T.average()});
        if (crypto && visible) aov->volumeCoverage[size_t(c.medium)] += before - T.average();
        const float left = T.average();
        if (russianRoulette(&T, sampler)) return Track::Continue;
        if (deep && visible) deep->coverage.push_back({{c.t, false}, left});
        if (crypto && visible) aov->volumeCoverage[size_t(c.medium)] += left;
        return Track::Stop;
    });
    if (crypto) aov->firstVolume = firstVisibleMedium(scene, ray, tEnd);
    if (!reached) T = SampledSpectrum(0.f);
    if (hit && reached && scene.geometry->holdout(*hit)) {
        // A holdout: no albedo and no coverage of its own; the plate behind it shows by T.
        if (!(depth < kInfinity)) depth = hit->t;
    } else if (hit && reached) {
        const Material& mat = scene.geometry->materialAt(*hit);
        const SampledWavelengths& w = ts.tracking.wavelengths();
        for (int i = 0; i < kSpectrumSamples; ++i) albedo[i] += T[i] * mat.albedo(w.lambda[i]);
        if (!(depth < kInfinity)) depth = hit->t;
        if (deep) deep->coverage.push_back({{hit->t, true}, T.average()});
        if (crypto) aov->shapeCoverage[size_t(hit->shape)] += T.average();
        T = SampledSpectrum(0.f);
    }
    if (!aov) return;
    aov->depth = depth;
    aov->albedo = albedo;
    aov->transmittance = T;
}

}  // namespace mirage
