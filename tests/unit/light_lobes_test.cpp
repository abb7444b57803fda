// The lobes about the lights (render/light_lobes.h) that the path tracer's lobe walks draw
// from: their draws follow their density (the walks' weights divide by it, so an error here
// would bias every guided render). The walks themselves are checked against the lit-box
// furnace (tests/physics/furnace_test.cpp).
#include "render/light_lobes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chi_square.h"
#include "light/dome_light.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;

RenderScene forwardMediumUnderLights() {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 0.1f, 5.f, 0.95f));
    scene.lights.push_back(makeDistantLight(Vec3(0.25f, -1.f, -0.15f), 1000.f, Spectrum(1.f)));
    scene.lights.push_back(makeQuadLight(Vec3(0.3f, 0.9f, 0.3f), Vec3(0.3f, 0.f, 0.f),
                                         Vec3(0.f, 0.f, 0.3f), 50.f, Spectrum(1.f)));
    return scene;
}

}  // namespace

// The lobes' density, checked against their draws by Pearson's χ² on an equal-area grid of
// the sphere (z × φ), and its integral over the sphere; the lobes of a near and a far lamp and
// a sun get unequal shares (the light each would send unblocked).
TEST(LightLobes, DrawsFollowTheirDensityChiSquare) {
    RenderScene scene = forwardMediumUnderLights();
    ASSERT_TRUE(guidesPaths(scene));
    scene.lights.push_back(makeQuadLight(Vec3(3.f, 0.9f, 3.f), Vec3(0.3f, 0.f, 0.f),
                                         Vec3(0.f, 0.f, 0.3f), 50.f, Spectrum(1.f)));
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.3f);
    const LightLobes lobes(scene, Vec3(0.45f, 0.4f, 0.5f), w);
    ASSERT_FALSE(lobes.empty());
    Sampler s(21, 0, 0);
    const test::SphereChiSquare c = test::sphereChiSquare<40, 80, 8>(
        1000000,
        [&] {
            const float u = s.get1D(), u1 = s.get1D(), u2 = s.get1D();
            return lobes.sample(u, u1, u2);
        },
        [&](double x, double y, double z) {
            return lobes.pdf(Vec3(float(x), float(y), float(z)));
        });
    EXPECT_NEAR(c.integral, 1.0, 2e-3);
    std::printf("lobes: ∫ pdf dω = %.5f, χ² %.1f on %d degrees of freedom\n", c.integral,
                c.fit.statistic, c.fit.dof);
    EXPECT_LT(c.fit.statistic, test::chiSquareCritical(c.fit.dof));
}

// Guiding is for strongly forward media with a light to guide to: not for smoke (HG g 0.5),
// nor under a dome alone.
TEST(LightLobes, GuideOnlyForwardMediaUnderLights) {
    RenderScene smoke;
    smoke.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 0.1f, 5.f, 0.5f));
    smoke.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), 1000.f, Spectrum(1.f)));
    EXPECT_FALSE(guidesPaths(smoke));
    RenderScene sea = forwardMediumUnderLights();
    EXPECT_TRUE(guidesPaths(sea));
    sea.lights.clear();
    EXPECT_FALSE(guidesPaths(sea));
}

// A sun in a sky map is a light to guide to (Light::lobe); a sky without one is not. Walks
// start at every vertex of a sea's paths, at fewer of a cloud's (lobeWalkStart).
TEST(LightLobes, GuideToASunInASkyMapAndStartFewerWalksInClouds) {
    const auto sky = [](bool sun) {
        LatLongImage img = test::flatSky(256, 128, 0.2f);
        if (sun)
            for (int c = 0; c < 3; ++c) img.rgb[3 * (size_t(40) * img.width + 100) + c] = 4e4f;
        return makeDomeLight(img, 1.f, Mat3(), DomeSettings{});
    };
    RenderScene cloud;
    cloud.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 0.05f, 4.95f, 0.85f));
    cloud.lights.push_back(sky(false));
    EXPECT_FALSE(guidesPaths(cloud));
    cloud.lights[0] = sky(true);
    ASSERT_TRUE(cloud.lights[0]->lobe().has_value());
    EXPECT_TRUE(guidesPaths(cloud));
    const LightLobes lobes(cloud, Vec3(0.5f), SampledWavelengths::sampleVisible(0.5f));
    ASSERT_FALSE(lobes.empty());
    EXPECT_NEAR(lobeWalkStart(cloud), 0.25f, 1e-5f);  // albedo 0.99
    RenderScene sea;
    sea.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 1.f, 4.f, 0.92f));
    EXPECT_EQ(lobeWalkStart(sea), 1.f);  // albedo 0.8
}
