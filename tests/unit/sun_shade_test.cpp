// Where a sky's sun is hidden from the media (render/sun_shade.h): the grid's optical depths
// against the closed form of a homogeneous cube, its rates, the same grid for any thread count,
// and volpath's mean with the rate set by it against the mean without it (the dark rule), on and
// off guided paths.
#include "render/sun_shade.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "light/dome_light.h"
#include "render/integrator.h"
#include "render/light_lobes.h"
#include "test_support.h"

namespace mirage {
namespace {

const Mat3 kXyz;

// A sky of 0.2 with a sun: one pixel of 300 at row 4 of 16 (45° up), which holds most of the
// dome's power (Light::lobe).
LatLongImage sunnySky() {
    LatLongImage img = test::flatSky(32, 16, 0.2f);
    for (int k = 0; k < 3; ++k) img.rgb[size_t(4 * img.width + 11) * 3 + size_t(k)] = 300.f;
    return img;
}

TEST(SunShade, OpticalDepthOfAHomogeneousCubeIsItsChordTowardsTheSun) {
    RenderScene scene = test::unitCubeScene(1.5f, 0.f);
    const Vec3 up = normalize(Vec3(0.3f, 1.f, 0.2f));
    const SunShade shade(scene, up);
    // Inside, away from the faces' half-voxel fall-off: τ = σt × the distance to the face the
    // ray leaves by (σt 1.5: at most 1.5 × 2.2 = 3.3, under the cap).
    for (float x : {-0.5f, 0.f, 0.4f})
        for (float y : {-0.6f, 0.f, 0.5f})
            for (float z : {-0.4f, 0.3f}) {
                const Vec3 p(x, y, z);
                float exit = kInfinity;
                for (int a = 0; a < 3; ++a)
                    if (up[a] != 0.f) exit = std::min(exit, ((up[a] > 0 ? 1.f : -1.f) - p[a]) / up[a]);
                const float tau = 1.5f * exit;
                EXPECT_NEAR(shade.opticalDepth(p), tau, 0.12f) << x << " " << y << " " << z;
                EXPECT_NEAR(shade.drawRate(p),
                            clamp(SunShade::kRateScale * std::exp(-tau), SunShade::kLeastRate, 1.f),
                            0.12f);
            }
    // Outside the medium on the sun's side nothing hides it; deep in a dense cube everything.
    EXPECT_EQ(shade.drawRate(Vec3(0.f, 0.99f, 0.f)), 1.f);
    RenderScene dense = test::unitCubeScene(40.f, 0.f);
    const SunShade deep(dense, up);
    EXPECT_EQ(deep.opticalDepth(Vec3(0.f)), SunShade::kDepthCap);
    EXPECT_EQ(deep.drawRate(Vec3(0.f)), SunShade::kLeastRate);
}

TEST(SunShade, TheSameGridForAnyThreadCount) {
    RenderScene scene = test::unitCubeScene(6.f, 0.f);
    const Vec3 d = normalize(Vec3(-0.4f, 0.8f, 0.5f));
    std::unique_ptr<SunShade> one, two;
    tbb::task_arena(1).execute([&] { one = std::make_unique<SunShade>(scene, d, 24); });
    tbb::task_arena(2).execute([&] { two = std::make_unique<SunShade>(scene, d, 24); });
    for (float x = -1.f; x <= 1.f; x += 0.13f)
        for (float y = -1.f; y <= 1.f; y += 0.17f)
            EXPECT_EQ(one->opticalDepth(Vec3(x, y, 0.1f)), two->opticalDepth(Vec3(x, y, 0.1f)));
}

// volpath's camera rays from 4 m onto the cube under the sunny sky, with the sky's draws at the
// shade's rate and by the dark rule, sample by sample: the two are estimates of one radiance, so
// their difference has mean 0. A draw that did not count 1/rate of itself, or an escape weighed
// without the rate, moves the shaded mean by tens of percent (the rate is 0.1 in the cube's
// depths): a draw counted once read +0.11 ± 0.02 of 0.48 unguided, +0.21 ± 0.08 of 0.85 guided
// over 6000 paths (30 000 here).
void expectSameMean(float g) {
    RenderScene on = test::unitCubeScene(8.f, g), off = test::unitCubeScene(8.f, g);
    on.lights.push_back(makeDomeLight(sunnySky(), 1.f, kXyz, {}));
    off.lights.push_back(makeDomeLight(sunnySky(), 1.f, kXyz, {}));
    off.sunShade = false;
    ASSERT_TRUE(SunShade::forScene(on));
    ASSERT_FALSE(SunShade::forScene(off));
    ASSERT_EQ(guidesPaths(on), g > 0.85f);
    auto withShade = makeVolPathIntegrator(), without = makeVolPathIntegrator();
    withShade->preprocess(on);
    without->preprocess(off);
    ThreadState tsOn(on), tsOff(off);
    test::SampleMean diff, plain;
    for (int i = 0; i < 30000; ++i) {
        Sampler a(31, uint64_t(i), 0), b(31, uint64_t(i), 0);
        const SampledWavelengths w = SampledWavelengths::sampleVisible(a.get1D());
        b.get1D();
        const float u1 = a.get1D(), u2 = a.get1D();
        b.get1D();
        b.get1D();
        const Vec3 o(0.f, 0.f, 4.f), target(0.8f * (2 * u1 - 1), 0.8f * (2 * u2 - 1), 0.f);
        const Ray ray{o, normalize(target - o), kInfinity};
        tsOn.tracking.setWavelengths(w);
        tsOff.tracking.setWavelengths(w);
        const float lOn = withShade->Li(on, ray, w, a, tsOn).L.average();
        const float lOff = without->Li(off, ray, w, b, tsOff).L.average();
        diff.add(double(lOn) - lOff);
        plain.add(lOff);
    }
    EXPECT_GT(plain.mean(), 0.1);
    EXPECT_NEAR(diff.mean(), 0.0, 4 * diff.standardError() + 1e-3 * plain.mean())
        << "g " << g << ": without " << plain.mean() << " ± " << plain.standardError();
}

TEST(SunShade, VolpathsMeanIsTheDarkRulesOnAndOffGuidedPaths) {
    expectSameMean(0.6f);
    expectSameMean(0.9f);
}

}  // namespace
}  // namespace mirage
