#include "render/light_lobes.h"

#include <algorithm>
#include <array>

#include "medium/phase.h"

namespace mirage {

namespace {

constexpr float kForwardPeak = 5.f;  // 1/sr: HG g ≈ 0.82
constexpr float kLobeG = 0.9f;
constexpr float kWalksPerPath = 25.f, kLeastStart = 0.1f;  // lobeWalkStart

}  // namespace

LightLobes::LightLobes(const RenderScene& scene, const Vec3& p, const SampledWavelengths& w) {
    float total = 0.f;
    for (const auto& light : scene.lights) {
        if (mCount == kMaxLights) break;
        LightSample ls;
        const std::optional<LightLobe> sun = light->lobe();
        if (sun) {
            ls.wi = sun->dir;
            ls.Li = SampledSpectrum(sun->irradiance);
        } else if (light->infinite() || !light->sampleLi(p, 0.5f, 0.5f, w, &ls)) {
            continue;
        }
        const float arriving = ls.Li.average();
        if (!(arriving > 0.f)) continue;
        mDirs[mCount] = ls.wi;
        mShare[mCount++] = arriving;
        total += arriving;
    }
    for (size_t i = 0; i < mCount; ++i) mShare[i] /= total;
}

Vec3 LightLobes::sample(float u, float u1, float u2) const {
    size_t i = 0;
    for (float below = mShare[0]; i + 1 < mCount && u >= below; below += mShare[++i]) {
    }
    return HGPhase(kLobeG).sample(mDirs[i], u1, u2, nullptr);
}

float LightLobes::pdf(const Vec3& wi) const {
    const HGPhase lobe(kLobeG);
    float sum = 0.f;
    for (size_t i = 0; i < mCount; ++i) sum += mShare[i] * lobe.eval(dot(mDirs[i], wi));
    return sum;
}

bool guidesPaths(const RenderScene& scene) {
    bool forward = false, light = false;
    for (const auto& m : scene.media) forward |= m->peakPhase() > kForwardPeak;
    for (const auto& l : scene.lights) light |= !l->infinite() || l->lobe().has_value();
    return forward && light;
}

float lobeWalkStart(const RenderScene& scene) {
    float albedo = 0.f;
    for (const auto& m : scene.media)
        for (const auto& c : m->shader().components) {
            const float s = c.sigmaS.maxValue(), t = c.sigmaA.maxValue() + s;
            if (t > 0.f) albedo = std::max(albedo, s / t);
        }
    return clamp(kWalksPerPath * (1.f - albedo), kLeastStart, 1.f);
}

}  // namespace mirage
