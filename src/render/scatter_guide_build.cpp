#include "render/scatter_guide_build.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "transport/tracking.h"

namespace mirage {

namespace {

// A cell guessed dark still holds points, at most 1/kGuideFloor times fewer than the light's
// brightest, so that where the coarse guess is wrong (a lit edge inside a dark cell) no rare
// point carries a huge weight. Measured on the race scene (docs/performance-history.md, "The
// light guide without shadow rays"): floors of 0.02 and 0.05 alike, 0.01 and 0.1 worse.
constexpr float kGuideFloor = 0.05f;
// Frame samples per guide cell: the guide's ~8 lookups and one coarse march per light a cell
// stay a small share of the frame's hundreds of lookups a sample (~20 ms of a 256² frame of 4
// samples per pixel, on two cores). 32³ cells are ~3 voxels of a 100-voxel cache each; 64³
// lowered the race scene's relMSE by 4 % more for ten times the build.
constexpr uint64_t kSamplesPerCell = 8;
constexpr int kMinResolution = 4, kMaxResolution = 32;

size_t cellIndex(int n, int i, int j, int k) { return (size_t(k) * n + j) * n + i; }

// The media's σt averaged over a cell (mean over the wavelengths of w, 1/m), from 2×2×2 points
// at the centres of its octants.
float meanExtinction(TrackingContext& ctx, const Bounds3& bounds, int n, int i, int j, int k) {
    const Vec3 cell = bounds.diagonal() / float(n);
    double sum = 0.0;
    for (int o = 0; o < 8; ++o) {
        const Vec3 p = bounds.lo + Vec3(cell.x * (i + 0.25f + 0.5f * (o & 1)),
                                        cell.y * (j + 0.25f + 0.5f * ((o >> 1) & 1)),
                                        cell.z * (k + 0.25f + 0.5f * (o >> 2)));
        for (size_t m = 0; m < ctx.size(); ++m) {
            const Medium& medium = ctx.medium(m);
            if (!medium.worldBounds().contains(p)) continue;
            MediumPoint mp;
            medium.eval(ctx.context(m).pointToObject(p), ctx.context(m), &mp);
            const float s = (mp.sigmaA + mp.sigmaS).average();
            if (s > 0.f) sum += std::min(double(s), kMaxSigma);
        }
    }
    return float(sum / 8.0);
}

// exp(−∫ σ̃ ds) from p along the unit direction d for `distance` (clipped to the bounds), with
// σ̃ the coarse grid of mean extinctions read at the nearest cell, stepped at half a cell.
float coarseTransmittance(const std::vector<float>& sigma, const Bounds3& bounds, int n,
                          const Vec3& p, const Vec3& d, float distance) {
    float t0, t1;
    if (!bounds.intersect(p, d, 0.f, distance, &t0, &t1)) return 1.f;
    const Vec3 cell = bounds.diagonal() / float(n);
    const float h = 0.5f * std::min({cell.x, cell.y, cell.z});
    const int steps = std::clamp(int(std::ceil((t1 - t0) / h)), 1, 4 * n);
    const float dt = (t1 - t0) / float(steps);
    auto index = [&](float x, float lo, float size) {
        return std::clamp(int((x - lo) / size), 0, n - 1);
    };
    double tau = 0.0;
    for (int s = 0; s < steps; ++s) {
        const Vec3 q = p + d * (t0 + (s + 0.5f) * dt);
        tau += sigma[cellIndex(n, index(q.x, bounds.lo.x, cell.x), index(q.y, bounds.lo.y, cell.y),
                               index(q.z, bounds.lo.z, cell.z))] *
               dt;
    }
    return float(std::exp(-tau));
}

// Σ_lights Li · T̃ at p: one light sample for a light at a point or a direction, four for the
// dome (its directions differ in how much smoke lies before them).
float guessLight(const RenderScene& scene, const std::vector<float>& sigma, const Bounds3& bounds,
                 int n, const Vec3& p, const SampledWavelengths& w) {
    double g = 0.0;
    for (const auto& light : scene.lights) {
        const int m = light->infinite() ? 2 : 1;
        for (int a = 0; a < m; ++a)
            for (int b = 0; b < m; ++b) {
                LightSample ls;
                if (!light->sampleLi(p, (a + 0.5f) / m, (b + 0.5f) / m, w, &ls)) continue;
                const float Li = ls.Li.average();
                if (!(Li > 0.f) || !std::isfinite(Li)) continue;
                g += Li * coarseTransmittance(sigma, bounds, n, p, ls.wi, ls.distance) / (m * m);
            }
    }
    return std::isfinite(g) ? float(g) : 0.f;
}

}  // namespace

int scatterGuideResolution(uint64_t frameSamples) {
    if (frameSamples == 0) return 0;
    const int n = int(std::cbrt(double(frameSamples / kSamplesPerCell)));
    return std::clamp(n, kMinResolution, kMaxResolution);
}

std::unique_ptr<ScatterGuide> buildScatterGuide(const RenderScene& scene, uint64_t frameSamples) {
    const int n = scatterGuideResolution(frameSamples);
    Bounds3 bounds;
    for (const auto& m : scene.media) bounds.expand(m->worldBounds());
    const Vec3 d = bounds.diagonal();
    if (n == 0 || scene.lights.empty() || bounds.empty() ||
        !(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)))
        return nullptr;
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    std::vector<float> sigma(size_t(n) * n * n), values(sigma.size());
    // Two sweeps over z-slices, each cell independent of the others: the same values for any
    // thread count.
    auto slices = [&](auto&& perCell) {
        tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& r) {
            TrackingContext ctx(scene.mediaPointers());
            ctx.setWavelengths(w);
            for (int k = r.begin(); k < r.end(); ++k)
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) perCell(ctx, i, j, k);
        });
    };
    slices([&](TrackingContext& ctx, int i, int j, int k) {
        sigma[cellIndex(n, i, j, k)] = meanExtinction(ctx, bounds, n, i, j, k);
    });
    slices([&](TrackingContext&, int i, int j, int k) {
        values[cellIndex(n, i, j, k)] =
            guessLight(scene, sigma, bounds, n, ScatterGuide::cellCentre(bounds, n, i, j, k), w);
    });
    return std::make_unique<ScatterGuide>(bounds, n, std::move(values), kGuideFloor);
}

}  // namespace mirage
