#include "render/guided_continuation.h"

#include <algorithm>
#include <array>

#include "medium/phase.h"

namespace mirage {

namespace {

constexpr float kForwardPeak = 5.f;  // 1/sr: HG g ≈ 0.82
constexpr float kSurfaceLobeG = 0.9f;
constexpr size_t kMaxGuides = 4;

// Unit directions from p towards the lights not at infinity (at most four).
size_t lightDirections(const RenderScene& scene, const Vec3& p, const SampledWavelengths& w,
                       std::array<Vec3, kMaxGuides>* dirs) {
    size_t n = 0;
    for (const auto& light : scene.lights) {
        LightSample ls;
        if (n < dirs->size() && !light->infinite() && light->sampleLi(p, 0.5f, 0.5f, w, &ls))
            (*dirs)[n++] = ls.wi;
    }
    return n;
}

// Which light lobe a guided sample uses: u in [½, 1) mapped onto n lights.
size_t pick(float u, size_t n) { return std::min(n - 1, size_t((2.f * u - 1.f) * float(n))); }

}  // namespace

bool guidesPaths(const RenderScene& scene) {
    bool forward = false, light = false;
    for (const auto& m : scene.media) forward |= m->peakPhase() > kForwardPeak;
    for (const auto& l : scene.lights) light |= !l->infinite();
    return forward && light;
}

bool continueAtDiffuse(const RenderScene& scene, const Material& material, const SurfaceHit& hit,
                       const Vec3& dir, const SampledWavelengths& w, Sampler& sampler,
                       PathThroughput* path, Ray* next) {
    std::array<Vec3, kMaxGuides> lights;
    const size_t n = lightDirections(scene, hit.p, w, &lights);
    if (n == 0)
        return continueAtSurface(material, hit, dir, w, TransportMode::Radiance, sampler, path,
                                 next);
    const Vec3 wo = -dir;
    const Frame frame(hit.ns);
    const Vec3 woL = frame.toLocal(wo);
    const float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
    const float ug = sampler.get1D();
    const HGPhase lobe(kSurfaceLobeG);
    Vec3 wi;
    if (ug < 0.5f) {
        BsdfSample bs;
        if (!material.sample(woL, uc, u1, u2, w, TransportMode::Radiance, &bs)) return false;
        wi = frame.toWorld(bs.wi);
    } else {
        wi = lobe.sample(lights[pick(ug, n)], u1, u2, nullptr);
    }
    // A Lambertian surface reflects only: a lobe's direction through it scores f = 0.
    if ((dot(wi, hit.ng) > 0.f) != (dot(wo, hit.ng) > 0.f)) return false;
    const Vec3 wiL = frame.toLocal(wi);
    float toLights = 0.f;
    for (size_t i = 0; i < n; ++i) toLights += lobe.eval(dot(lights[i], wi));
    const float mixture = 0.5f * material.pdf(woL, wiL) + 0.5f * toLights / float(n);
    if (!(mixture > 0.f)) return false;
    path->beta *= material.eval(woL, wiL, w) * (std::abs(wiL.z) / mixture);
    path->history.scatter(true);
    *next = spawnRay(hit, wi);
    return true;
}

}  // namespace mirage
