// The lobes towards lamps inside media (render/light_lobes.h, volpath.cpp "Lobes towards
// lamps"): their draws follow their density (χ²), only lamps with medium about them get them,
// volpath's mean is the same with and without them, a pixel whose paths pass the lamp only after
// a bounce loses its fireflies, and a render gives the same bits on one thread and on two.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>

#include "chi_square.h"
#include "render/light_lobes.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;

// A 1 m box of fog (σs 1.5/m, albedo 0.9, HG g 0.3) with a point light at its centre.
RenderScene lampInFog() {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 0.15f, 1.35f, 0.3f));
    scene.lights.push_back(makePointLight(Vec3(0.5f), 50.f, Spectrum(1.f)));
    return scene;
}

// volpath of paths up to `depth` vertices, its lamp lobes on (preprocessed, as every frame is)
// or off (never preprocessed: no lamps found).
std::unique_ptr<Integrator> volpath(const RenderScene& scene, bool lobes, int depth = 16) {
    auto integrator = makeVolPathIntegrator(depth);
    if (lobes) integrator->preprocess(scene);
    return integrator;
}

}  // namespace

// Two lamps of unequal power and distance: the mixture's density against its draws by Pearson's
// χ² on an equal-area grid of the sphere (fine, since the density grows as 1/θ towards each
// lamp), and its integral over the sphere.
TEST(LampLobes, DrawsFollowTheirDensityChiSquare) {
    const std::vector<MediumLamp> lamps = {{Vec3(0.9f, 0.3f, 0.2f), 100.f},
                                           {Vec3(-0.4f, 0.7f, -0.9f), 300.f}};
    const LightLobes lobes = LightLobes::towardsLamps(lamps, Vec3(0.1f, 0.2f, 0.05f));
    ASSERT_FALSE(lobes.empty());
    Sampler s(5, 0, 0);
    const test::SphereChiSquare c = test::sphereChiSquare<40, 80, 16>(
        1000000,
        [&] {
            const float u = s.get1D(), u1 = s.get1D(), u2 = s.get1D();
            return lobes.sample(u, u1, u2);
        },
        [&](double x, double y, double z) {
            return lobes.pdf(normalize(Vec3(float(x), float(y), float(z))));
        });
    std::printf("lamp lobes: ∫ pdf dω = %.5f, χ² %.1f on %d degrees of freedom\n", c.integral,
                c.fit.statistic, c.fit.dof);
    EXPECT_NEAR(c.integral, 1.0, 1e-2);
    EXPECT_LT(c.fit.statistic, test::chiSquareCritical(c.fit.dof));
    // Nothing is drawn more than 90° from the lamp its lobe is about.
    EXPECT_EQ(lobes.pdf(normalize(Vec3(-1.f, 0.f, 1.f))), 0.f);
}

// A lamp gets lobes where medium is about it: inside the fog, or within a cell of it; not a
// spot a metre off the box, nor a lamp in an empty region of the box.
TEST(LampLobes, OnlyLampsWithMediumAboutThem) {
    RenderScene scene = lampInFog();
    EXPECT_EQ(lampsInMedia(scene).size(), 1u);
    scene.lights.push_back(makeSpotLight(Vec3(2.f, 0.5f, 0.5f), Vec3(-1.f, 0.f, 0.f), 50.f, 10.f,
                                         15.f, Spectrum(1.f)));
    EXPECT_EQ(lampsInMedia(scene).size(), 1u);
    RenderScene hollow;
    hollow.media.push_back(test::gridMedium([](int i, int, int) { return i < 8 ? 1.f : 0.f; }, 0,
                                            31, kH, 0.15f, 1.35f, 0.3f));
    hollow.lights.push_back(makePointLight(Vec3(0.8f, 0.5f, 0.5f), 50.f, Spectrum(1.f)));
    EXPECT_TRUE(lampsInMedia(hollow).empty());
    hollow.lights.push_back(makePointLight(Vec3(0.2f, 0.5f, 0.5f), 50.f, Spectrum(1.f)));
    EXPECT_EQ(lampsInMedia(hollow).size(), 1u);
}

// The mean of a ray through the fog, at each of the path's four wavelengths, with and without
// the lamp's lobes: the mixture reweighs the continuations, it must not move the mean.
TEST(LampLobes, KeepVolpathsMeanPerWavelength) {
    const RenderScene scene = lampInFog();
    const Ray ray{Vec3(-0.2f, 0.7f, 0.45f), Vec3(1, 0, 0), kInfinity};
    const auto on = test::estimateAlongRayPerWavelength(*volpath(scene, true), scene, ray, 40000);
    const auto off = test::estimateAlongRayPerWavelength(*volpath(scene, false), scene, ray, 40000);
    for (int k = 0; k < kSpectrumSamples; ++k) {
        std::printf("λ%d: lobes %.5g ± %.2g, phase alone %.5g ± %.2g\n", k, on[k].mean, on[k].se,
                    off[k].mean, off[k].se);
        EXPECT_NEAR(on[k].mean, off[k].mean, 4 * std::hypot(on[k].se, off[k].se)) << "λ" << k;
    }
}

// A ray 0.45 m from the lamp, through a corner of the fog: its light after one bounce comes from
// segments that may pass the lamp at any distance D, each estimated ∝ 1/D by its equiangular
// point. Drawn by the phase function alone, their second moment diverges as log D (fireflies);
// with the lobes it is bounded. Measured over 10⁵ paths: the largest sample 292 × the mean
// against 3520 ×, the standard error 5.2× lower (27× less variance).
TEST(LampLobes, APixelLitPastTheLampAfterABounceLosesItsFireflies) {
    const RenderScene scene = lampInFog();
    const Ray ray{Vec3(-0.2f, 0.95f, 0.5f), Vec3(1, 0, 0), kInfinity};
    const test::RayEstimate on = test::estimateAlongRay(*volpath(scene, true), scene, ray, 100000);
    const test::RayEstimate off =
        test::estimateAlongRay(*volpath(scene, false), scene, ray, 100000);
    std::printf(
        "lobes %.5g ± %.2g (largest %.1f × mean); phase alone %.5g ± %.2g (largest %.1f "
        "× mean)\n",
        on.mean, on.se, on.largest / on.mean, off.mean, off.se, off.largest / off.mean);
    EXPECT_NEAR(on.mean, off.mean, 4 * std::hypot(on.se, off.se));
    EXPECT_LT(on.largest * 6, off.largest);
    EXPECT_LT(on.se * 3, off.se);
}

TEST(LampLobes, RenderTheSameBitsOnOneAndTwoThreads) {
    RenderScene scene = lampInFog();
    scene.camera.position = Vec3(0.5f, 0.5f, 3.f);
    scene.camera.lookAt = Vec3(0.5f);
    const auto integrator = volpath(scene, true);
    const RenderSettings settings = test::smallRenderSettings(4, 9, 16, 16);
    auto withThreads = [&](size_t threads) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
        return render(scene, *integrator, settings, nullptr);
    };
    EXPECT_TRUE(test::sameFilm(withThreads(1), withThreads(2)));
}
