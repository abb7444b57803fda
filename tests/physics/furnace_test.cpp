// Furnace tests for the integrators. Inside an optically deep, uniform, emitting and
// scattering medium, the radiative transfer equation dL/ds = −σt L + σs L + σa Le = 0 gives
// L = Le whatever the albedo (Kirchhoff: the medium is a blackbody cavity). The reference path
// tracer must find Le; the single-scattering integrator, which stops after the first event,
// must find exactly the emitted part of the first flight, (σa/σt)·Le.
#include <gtest/gtest.h>

#include <cmath>

#include "render/integrator.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr float kTemperature = 1500.f;  // K

RenderScene furnace(float sigmaA, float sigmaS, float g) {
    RenderScene scene;
    ShaderDesc s = test::greyShader(sigmaA, sigmaS, g);
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    s.emission = e;
    // A 2 m cube (64 voxels of 1/32 m), centred on the origin.
    auto one = [](int, int, int) { return 1.f; };
    auto hot = [](int, int, int) { return kTemperature; };
    Vec3d origin(-1.0, -1.0, -1.0);
    std::vector<FloatGrid> grids{test::makeGrid(one, 0, 63, 1.0 / 32, origin, "density"),
                                 test::makeGrid(hot, 0, 63, 1.0 / 32, origin, "temperature")};
    scene.media.push_back(std::make_unique<Medium>(s, std::move(grids), Transform(), 1.f, 16));
    return scene;
}

// Mean of L(λ)/Le(λ) over samples of rays leaving the centre, with its standard error.
std::pair<double, double> ratioToLe(const Integrator& integrator, const RenderScene& scene,
                                    int n) {
    ThreadState ts(scene);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        Sampler s(9, uint64_t(i), 0);
        SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        Vec3 d = sampleUniformSphere(s.get1D(), s.get1D());
        RadianceSample r = integrator.Li(scene, Ray{Vec3(0.01f, 0.02f, 0.03f), d, kInfinity}, w, s, ts);
        double ratio = 0;
        for (int k = 0; k < kSpectrumSamples; ++k)
            ratio += r.L[k] / (planck(w.lambda[k], kTemperature) * 1e-9) / kSpectrumSamples;
        sum += ratio;
        sum2 += ratio * ratio;
    }
    double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

}  // namespace

TEST(Furnace, VolPathFindsTheBlackbodyRadianceAtAnyAlbedo) {
    // σt = 20/m: the walls are 20 mean free paths and ≥ 9 diffusion lengths away, so the
    // leakage is below 1e-4.
    for (float albedo : {0.5f, 0.9f}) {
        RenderScene scene = furnace(20.f * (1 - albedo), 20.f * albedo, 0.5f);
        auto integrator = makeVolPathIntegrator();
        auto [mean, se] = ratioToLe(*integrator, scene, 20000);
        EXPECT_NEAR(mean, 1.0, 4 * se + 2e-3) << "albedo " << albedo << " ± " << se;
        EXPECT_EQ(integrator->stats().cappedPaths, 0u);
    }
}

TEST(Furnace, SingleScatteringKeepsOnlyTheFirstFlightEmission) {
    const float albedo = 0.7f;
    RenderScene scene = furnace(20.f * (1 - albedo), 20.f * albedo, 0.f);
    auto integrator = makeSingleScatterIntegrator();
    auto [mean, se] = ratioToLe(*integrator, scene, 20000);
    EXPECT_NEAR(mean, 1.0 - albedo, 4 * se + 2e-3) << "± " << se;
}
