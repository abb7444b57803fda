// The data passes of a camera ray (render/camera_ray_data.h) against closed forms, whoever walks
// the ray: the record walking it alone, the single-scattering integrator handing over its
// whole walk, and volpath handing over its walk up to the first real collision, after which the
// record goes on alone. A ramp of density makes the majorant exceed σt in every cell, so that
// walks go on past null collisions and volpath's stops fall anywhere along the ray.
#include "render/camera_ray_data.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "test_support.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;
constexpr float kSigmaA = 0.3f, kSigmaS = 1.2f;

// Density rising from 0 to 1 along x across the 1 m box.
RenderScene rampScene() {
    RenderScene scene;
    scene.media.push_back(test::gridMedium([](int i, int, int) { return (i + 0.5f) / 32.f; }, 0, 31,
                                           kH, kSigmaA, kSigmaS));
    scene.lights.push_back(makeDistantLight(Vec3(0, -1, 0), 470.f, Spectrum(1.f)));
    return scene;
}

struct DataMeans {
    double T = 0, albedo = 0, depth = 0, depthSq = 0;
    int finiteDepths = 0;
};

// Means over n samples of the record of `ray`, with `walk` (may be null) handed the record as
// the integrator's walk of the camera ray.
DataMeans recordMeans(
    const RenderScene& scene, const Ray& ray, int n,
    const std::function<void(Sampler&, const SampledWavelengths&, ThreadState&)>& walk) {
    ThreadState ts(scene);
    DataMeans m;
    for (int i = 0; i < n; ++i) {
        Sampler sampler(SamplerKind::Random, 7, 0, uint64_t(i));
        Sampler data(SamplerKind::Random, 8, 0, uint64_t(i));
        const SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
        ts.tracking.setWavelengths(w);
        AovSample aov;
        CameraRayData record(scene, ray, w, data, ts, &aov, nullptr);
        ts.cameraData = &record;
        if (walk) walk(sampler, w, ts);
        ts.cameraData = nullptr;
        record.finish();
        m.T += aov.transmittance[0] / n;
        m.albedo += aov.albedo[0] / n;
        if (std::isfinite(aov.depth)) {
            m.depth += aov.depth;
            m.depthSq += double(aov.depth) * aov.depth;
            ++m.finiteDepths;
        }
    }
    return m;
}

}  // namespace

TEST(CameraRayData, EveryWalkerGivesTheClosedFormsOfTheRay) {
    const RenderScene scene = rampScene();
    // Along +x through the box's middle: τ = σt ∫₀¹ x dx = σt / 2 (the grid's trilinear ramp).
    const Ray ray{Vec3(-0.5f, float(16 * kH), float(16 * kH)), Vec3(1, 0, 0), kInfinity};
    const double tau = 0.5 * (kSigmaA + kSigmaS);
    const double T = std::exp(-tau), albedo = kSigmaS / (kSigmaA + kSigmaS) * (1.0 - T);

    const auto single = makeSingleScatterIntegrator();
    const auto volpath = makeVolPathIntegrator();
    auto by = [&](const Integrator& integrator) {
        return
            [&scene, &ray, &integrator](Sampler& s, const SampledWavelengths& w, ThreadState& ts) {
                integrator.Li(scene, ray, w, s, ts);
            };
    };
    const int n = 40000;
    const DataMeans alone = recordMeans(scene, ray, n, nullptr);
    const DataMeans bySingle = recordMeans(scene, ray, n, by(*single));
    const DataMeans byVolpath = recordMeans(scene, ray, n, by(*volpath));
    const char* const names[] = {"alone", "single", "volpath"};
    const DataMeans* const walkers[] = {&alone, &bySingle, &byVolpath};
    for (int k = 0; k < 3; ++k) {
        // Ratio tracking's T ∈ [0, 1] before roulette: σ ≤ 1/(2√n) bounds the standard error.
        EXPECT_NEAR(walkers[k]->T, T, 4 * 0.5 / std::sqrt(n)) << names[k];
        EXPECT_NEAR(walkers[k]->albedo, albedo, 0.01) << names[k];
    }
    // A sample's depth is where its own T first falls to ½: a function of where the tentative
    // collisions fall, whose law is the same whoever walks the ray.
    ASSERT_GT(alone.finiteDepths, 100);
    const double depth = alone.depth / alone.finiteDepths;
    const double spread = std::sqrt(alone.depthSq / alone.finiteDepths - depth * depth) /
                          std::sqrt(alone.finiteDepths);
    for (int k = 1; k < 3; ++k) {
        EXPECT_NEAR(double(walkers[k]->finiteDepths) / n, double(alone.finiteDepths) / n, 0.015)
            << names[k];
        EXPECT_NEAR(walkers[k]->depth / walkers[k]->finiteDepths, depth, 6 * spread) << names[k];
    }
}
