#include "render/sun_shade.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "render/integrator.h"

namespace mirage {

namespace {

// The optical depth from p along d through every medium, up to kDepthCap: each majorant cell's
// segment by σt at its middle (the still medium, averaged over the wavelengths), the control of
// residual ratio tracking (transport/tracking.cpp), deterministic: a function of the ray alone.
float depthAlong(TrackingContext& ctx, const Vec3& p, const Vec3& d) {
    float tau = 0.f;
    const Ray world{p, d, kInfinity};
    for (size_t i = 0; i < ctx.size() && tau < SunShade::kDepthCap; ++i) {
        const Medium& m = ctx.medium(i);
        Medium::Context& mc = ctx.context(i);
        const Ray r = mc.toObject(world);
        m.majorant().traverse(r.o, r.d, 0.f, kInfinity, [&](float t0, float t1, float sigmaMaj) {
            if (!(sigmaMaj > 0.f)) return true;
            MediumPoint mp;
            m.evalStill(r.at(0.5f * (t0 + t1)), mc, &mp);
            tau += (mp.sigmaA + mp.sigmaS).average() * (t1 - t0);
            return tau < SunShade::kDepthCap;
        });
    }
    return std::min(tau, SunShade::kDepthCap);
}

// The box the grid lies over: the media's world bounds.
Bounds3 mediaBounds(const RenderScene& scene) {
    Bounds3 bounds;
    for (const auto& m : scene.media) bounds.expand(m->worldBounds());
    return bounds;
}

}  // namespace

std::optional<Vec3> SunShade::sunOf(const RenderScene& scene) {
    if (!scene.sunShade) return std::nullopt;
    const Bounds3 bounds = mediaBounds(scene);
    for (int a = 0; a < 3; ++a)  // no media, or a medium without bounds: no grid to lay
        if (!std::isfinite(bounds.lo[a]) || !std::isfinite(bounds.hi[a]) ||
            !(bounds.hi[a] > bounds.lo[a]))
            return std::nullopt;
    for (const auto& light : scene.lights)
        if (const std::optional<LightLobe> sun = light->lobe()) return sun->dir;
    return std::nullopt;
}

std::unique_ptr<SunShade> SunShade::forScene(const RenderScene& scene) {
    const std::optional<Vec3> sun = sunOf(scene);
    return sun ? std::make_unique<SunShade>(scene, *sun) : nullptr;
}

SunShade::SunShade(const RenderScene& scene, const Vec3& towardsSun, int res)
    : mBounds(mediaBounds(scene)), mRes(res) {
    mDepth.resize(size_t(res) * res * res);
    // One slice of cells per task, each with its own medium contexts; every cell's depth is a
    // function of its centre alone, so the grid is the same for any thread count.
    tbb::parallel_for(tbb::blocked_range<int>(0, res), [&](const tbb::blocked_range<int>& zs) {
        ThreadState ts(scene);
        for (int z = zs.begin(); z < zs.end(); ++z)
            for (int y = 0; y < res; ++y)
                for (int x = 0; x < res; ++x) {
                    const int cell[3] = {x, y, z};
                    Vec3 p;
                    for (int a = 0; a < 3; ++a)
                        p[a] = mBounds.lo[a] +
                               (float(cell[a]) + 0.5f) / float(res) * (mBounds.hi[a] - mBounds.lo[a]);
                    mDepth[(size_t(z) * res + y) * res + x] = depthAlong(ts.tracking, p, towardsSun);
                }
    });
}

float SunShade::opticalDepth(const Vec3& p) const {
    int i[3], j[3];
    float f[3];
    for (int a = 0; a < 3; ++a) {
        const float extent = mBounds.hi[a] - mBounds.lo[a];
        const float c = extent > 0.f ? (p[a] - mBounds.lo[a]) / extent * float(mRes) - 0.5f : 0.f;
        const float q = clamp(c, 0.f, float(mRes - 1));
        i[a] = std::min(int(q), mRes - 1);
        j[a] = std::min(i[a] + 1, mRes - 1);
        f[a] = q - float(i[a]);
    }
    auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    auto row = [&](int y, int z) { return lerp(at(i[0], y, z), at(j[0], y, z), f[0]); };
    auto plane = [&](int z) { return lerp(row(i[1], z), row(j[1], z), f[1]); };
    return lerp(plane(i[2]), plane(j[2]), f[2]);
}

float SunShade::drawRate(const Vec3& p) const {
    return clamp(kRateScale * std::exp(-opticalDepth(p)), kLeastRate, 1.f);
}

}  // namespace mirage
