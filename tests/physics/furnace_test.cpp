// Furnace tests for the integrators. Inside an optically deep, uniform, emitting and
// scattering medium, the radiative transfer equation dL/ds = −σt L + σs L + σa Le = 0 gives
// L = Le whatever the albedo (Kirchhoff: the medium is a blackbody cavity). The reference path
// tracer must find Le; the single-scattering integrator, which stops after the first event,
// must find exactly the emitted part of the first flight, (σa/σt)·Le.
// The same holds for light from outside: a conservative medium (albedo 1) inside a closed box
// of walls of radiance L has L everywhere, in every direction, whatever its phase function —
// the check that the path tracer's lobe walks (render/volpath.cpp) add no light twice. A white
// Lambertian ball in the medium (albedo 1, where lobe walks start too) keeps that answer.
#include <gtest/gtest.h>

#include <cmath>

#include "render/integrator.h"
#include "render/light_lobes.h"
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

namespace {

// A 2 m cube of conservative, strongly forward medium (σs = 5/m, HG g 0.95: p(0) ≈ 62/sr, so
// volpath guides its paths towards the lights) inside a 2.5 m box of six inward quad lights of
// radiance 1 (spectrally flat); with a white ball of radius kBall at kBallAt in it, or without.
constexpr float kBall = 0.4f;
const Vec3 kBallAt(0.5f, 0.f, 0.f);

RenderScene litBox(bool ball) {
    RenderScene scene;
    if (ball) {
        scene.geometry = std::make_unique<GeometryScene>();
        const int white = scene.geometry->addMaterial(Material::diffuse("white", Spectrum(1.f)));
        scene.geometry->addSphere(kBallAt, kBall, white);
        scene.geometry->commit();
    }
    auto one = [](int, int, int) { return 1.f; };
    scene.media.push_back(test::gridMedium(one, 0, 63, 1.0 / 32, 0.f, 5.f, 0.95f,
                                           Transform::translate(Vec3d(-1.0, -1.0, -1.0))));
    const float h = 1.25f, side = 2.f * h, area = side * side;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.f, 1.f}) {
            Vec3 n(0.f), a(0.f), b(0.f);
            n[axis] = -sign;  // inward
            a[(axis + 1) % 3] = side;
            b[(axis + 2) % 3] = side;
            if (dot(cross(a, b), n) < 0.f) std::swap(a, b);
            Vec3 corner(-h);
            corner[axis] = sign * h;
            scene.lights.push_back(makeQuadLight(corner, a, b, float(M_PI) * area, Spectrum(1.f)));
        }
    return scene;
}

}  // namespace

class LitBox : public ::testing::TestWithParam<bool> {};

TEST_P(LitBox, VolPathLobeWalksFindTheWallsRadiance) {
    const bool ball = GetParam();
    const RenderScene scene = litBox(ball);
    ASSERT_TRUE(guidesPaths(scene));
    auto integrator = makeVolPathIntegrator();
    ThreadState ts(scene);
    const Vec3 o(0.01f, 0.02f, 0.03f);
    const float sigma = 5.f;
    const float ballCone = std::sqrt(1.f - kBall * kBall / dot(kBallAt - o, kBallAt - o));
    test::SampleMean ratio;
    for (int i = 0; i < 16000; ++i) {
        Sampler s(11, uint64_t(i), 0);
        const SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        // With the ball, the rays that see it (a cone about it), so that what the estimate
        // gathers from the ball's surface is most of each sample.
        const float u1 = s.get1D(), u2 = s.get1D();
        const Vec3 d = ball ? sampleUniformCone(normalize(kBallAt - o), ballCone, u1, u2)
                            : sampleUniformSphere(u1, u2);
        const RadianceSample r = integrator->Li(scene, Ray{o, d, kInfinity}, w, s, ts);
        // The walls' radiance at these wavelengths, and the part of it that a camera ray
        // missing the ball sees unscattered (lights are reached by next-event estimates, not
        // by camera rays).
        LightSample ls;
        ASSERT_TRUE(scene.lights[0]->sampleLi(o, 0.5f, 0.5f, w, &ls));
        float exit = kInfinity;
        for (int a = 0; a < 3; ++a)
            if (d[a] != 0.f) exit = std::min(exit, ((d[a] > 0.f ? 1.f : -1.f) - o[a]) / d[a]);
        const Vec3 oc = o - kBallAt;
        const float b = dot(oc, d), c = dot(oc, oc) - kBall * kBall;
        const bool hitsBall = ball && b < 0.f && b * b >= c;
        double v = 0;
        for (int k = 0; k < kSpectrumSamples; ++k)
            v += r.L[k] / (ls.Li[k] * ls.pdf) / kSpectrumSamples;
        if (!hitsBall) v += std::exp(-sigma * exit);
        ratio.add(v);
    }
    const double mean = ratio.mean(), se = ratio.standardError();
    std::printf("lit box%s: L / L_walls = %.4f ± %.4f\n", ball ? " with a white ball" : "", mean,
                se);
    EXPECT_NEAR(mean, 1.0, 4 * se + 2e-3);
    EXPECT_EQ(integrator->stats().cappedPaths, 0u);
}

INSTANTIATE_TEST_SUITE_P(Furnace, LitBox, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) {
                             return p.param ? "WithAWhiteBall" : "MediumAlone";
                         });
