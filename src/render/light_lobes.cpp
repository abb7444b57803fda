#include "render/light_lobes.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/sampling.h"
#include "light/lamp.h"
#include "medium/phase.h"

namespace mirage {

namespace {

constexpr float kForwardPeak = 5.f;  // 1/sr: HG g ≈ 0.82
constexpr float kLobeG = 0.9f;
constexpr float kLampLobeAngle = 0.5f * kPi;  // a lamp lobe's largest angle to the lamp
constexpr float kWalksPerPath = 25.f, kLeastStart = 0.1f;  // lobeWalkStart

// Whether some majorant cell of `medium` within one cell and `radius` (m) of the world point p
// holds any medium.
bool mediumAround(const Medium& medium, const Vec3& p, float radius) {
    const MajorantGrid& grid = medium.majorant();
    const Vec3 q = medium.objectToWorld().inverse().point(p), size = grid.cellSize();
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        const float reach = 1.f + radius / size[a];
        const float c = (q[a] - grid.bounds().lo[a]) / size[a];
        lo[a] = std::max(0, int(std::floor(c - reach)));
        hi[a] = std::min(grid.res(a) - 1, int(std::floor(c + reach)));
        if (lo[a] > hi[a]) return false;
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x)
                if (grid.cell(x, y, z) > 0.f) return true;
    return false;
}

}  // namespace

std::vector<MediumLamp> lampsInMedia(const RenderScene& scene) {
    std::vector<MediumLamp> lamps;
    if (!scene.equiangular || guidesPaths(scene)) return lamps;
    const Bounds3 bounds = scene.bounds();
    for (const auto& light : scene.lights) {
        const std::optional<LightOrigin> origin = light->origin();
        if (!origin) continue;
        const auto* shape = dynamic_cast<const Lamp*>(light.get());
        const float radius = shape ? shape->radius() : 0.f;
        const float power = light->emittedPower(bounds);
        bool inside = false;
        for (const auto& m : scene.media) inside = inside || mediumAround(*m, origin->p, radius);
        if (inside && power > 0.f) lamps.push_back(MediumLamp{origin->p, power});
    }
    std::stable_sort(lamps.begin(), lamps.end(),
                     [](const MediumLamp& a, const MediumLamp& b) { return a.power > b.power; });
    if (lamps.size() > 4) lamps.resize(4);
    return lamps;
}

void LightLobes::add(const Vec3& dir, float weight) {
    mDirs[mCount] = dir;
    mShare[mCount++] = weight;
}

void LightLobes::normalise() {
    float total = 0.f;
    for (size_t i = 0; i < mCount; ++i) total += mShare[i];
    for (size_t i = 0; i < mCount; ++i) mShare[i] /= total;
}

LightLobes::LightLobes(const RenderScene& scene, const Vec3& p, const SampledWavelengths& w) {
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
        if (arriving > 0.f) add(ls.wi, arriving);
    }
    normalise();
}

LightLobes LightLobes::towardsLamps(const std::vector<MediumLamp>& lamps, const Vec3& p) {
    LightLobes lobes;
    lobes.mShape = Shape::Lamp;
    for (const MediumLamp& lamp : lamps) {
        if (lobes.mCount == kMaxLights) break;
        const Vec3 to = lamp.p - p;
        const float r = length(to);
        if (r > 0.f && std::isfinite(r)) lobes.add(to / r, lamp.power / r);
    }
    lobes.normalise();
    return lobes;
}

Vec3 LightLobes::sample(float u, float u1, float u2) const {
    size_t i = 0;
    for (float below = mShare[0]; i + 1 < mCount && u >= below; below += mShare[++i]) {
    }
    if (mShape == Shape::Lamp) return sampleUniformAngle(mDirs[i], kLampLobeAngle, u1, u2);
    return HGPhase(kLobeG).sample(mDirs[i], u1, u2, nullptr);
}

float LightLobes::pdf(const Vec3& wi) const {
    const HGPhase lobe(kLobeG);
    float sum = 0.f;
    for (size_t i = 0; i < mCount; ++i)
        sum += mShare[i] * (mShape == Shape::Lamp ? uniformAnglePdf(mDirs[i], kLampLobeAngle, wi)
                                                  : lobe.eval(dot(mDirs[i], wi)));
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
