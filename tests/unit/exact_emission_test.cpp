// Blackbody emission in grey media filmed in its exact colour (render/achromatic_film.h,
// spectrum/blackbody_xyz.h): the table against the film's own sum, the shortcut taken only for
// an integrator that records emission with its temperature, the same mean per channel as the
// spectral film, every pixel in the blackbody's exact colour, and a constant dome counted as a
// light of one colour.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "light/dome_light.h"
#include "render/achromatic_film.h"
#include "render/photon_integrator.h"
#include "render/renderer.h"
#include "spectrum/blackbody_xyz.h"
#include "spectrum/cie.h"
#include "test_support.h"

using namespace mirage;

namespace {

auto ball = [](int i, int j, int k) {
    float x = (i - 11.5f) / 12.f, y = (j - 11.5f) / 12.f, z = (k - 11.5f) / 12.f;
    return std::max(0.f, 1.f - (x * x + y * y + z * z));
};

// A ball of grey smoke glowing at 1500 K throughout, or (graded) at 1800 K in its centre
// cooling to 600 K at its edge; no light. The temperature grid reaches two voxels past the
// density's, so that its trilinear value is 1500 K wherever the smoke is: its indices start at 0
// and its origin two voxels back, as test::makeGrid takes no negative index.
RenderScene glowingBall(bool graded = true) {
    ShaderDesc s = test::greyShader(2.f, 6.f);
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    s.emission = e;
    std::vector<FloatGrid> grids;
    for (const std::string& slot : s.gridSlots())
        grids.push_back(slot == "temperature"
                            ? test::makeGrid(
                                  [graded](int i, int j, int k) {
                                      return graded ? 600.f + 1200.f * ball(i - 2, j - 2, k - 2)
                                                    : 1500.f;
                                  },
                                  0, 27, 1.0 / 24, Vec3d(-2.0 / 24), "temperature")
                            : test::makeGrid(ball, 0, 23, 1.0 / 24));
    RenderScene scene;
    scene.media.push_back(std::make_unique<Medium>(s, std::move(grids), Transform(), 1.f, 16));
    scene.camera.position = Vec3(0.5f, 0.55f, 3.f);
    scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
    scene.camera.fovDeg = 24.f;
    return scene;
}

Vec3d pixelMean(const Film::Pixel& p) {
    return Vec3d(p.xyz[0], p.xyz[1], p.xyz[2]) / double(std::max<uint64_t>(p.samples, 1));
}

}  // namespace

// At 400 temperatures log-spaced over the table's 300–100 000 K (none on an entry: 1.57 of
// them per interval) and at its ends and beyond.
TEST(BlackbodyXyz, MatchesTheFilmsSumOverTemperatures) {
    std::vector<double> temperatures;
    for (int i = 0; i < 400; ++i)
        temperatures.push_back(300.0 * std::pow(100000.0 / 300.0, (i + 0.37) / 400.0));
    for (double T : {300.0, 100000.0, 120000.0, 300000.0}) temperatures.push_back(T);
    double worst = 0.0;
    // (Far below 300 K the visible glow underflows float: XYZ of 150 K is ~1e-90.)
    for (double T : temperatures) {
        Vec3d sum(0.0);
        for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
            const double l = kLambdaMin + double(i);
            sum += Vec3d(cieXyz(float(l))) * (planck(l, T) * 1e-9);
        }
        sum = sum / double(kCieYIntegral);
        const Vec3 got = blackbodyXyz(float(T));
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(got[c] / sum[c], 1.0, 1e-5) << T << " K, " << c;
            worst = std::max(worst, std::abs(got[c] / sum[c] - 1.0));
        }
    }
    std::printf("largest relative error of the table: %.3g\n", worst);
    EXPECT_EQ(blackbodyXyz(0.f).y, 0.f);
    EXPECT_EQ(blackbodyXyz(-5.f).y, 0.f);
}

TEST(ExactEmission, TakenForVolpathOnGreyGlowingMediaOnly) {
    const RenderScene scene = glowingBall();
    const auto volpath = makeVolPathIntegrator();
    const auto film = AchromaticFilm::forScene(scene, *volpath);
    ASSERT_TRUE(film);
    EXPECT_TRUE(film->exactEmission());
    EXPECT_EQ(film->colours(), 0u);
    std::string why;
    EXPECT_FALSE(sampledColour(scene, integratorInfo("volpath"), &why));
    EXPECT_NE(why.find("exact XYZ"), std::string::npos) << why;
    // The photon mapper's camera part films emission at the sample's wavelengths.
    EXPECT_FALSE(
        AchromaticFilm::forScene(scene, *makePhotonIntegrator(PhotonIntegratorSettings())));
    EXPECT_TRUE(sampledColour(scene, integratorInfo("photon"), &why));
    EXPECT_NE(why.find("emission"), std::string::npos) << why;
    // Lit by a constant dome too: a light of one colour beside the glow.
    RenderScene lit = glowingBall();
    lit.lights.push_back(makeDomeLight(Spectrum(0.3f), DomeSettings{}));
    const auto both = AchromaticFilm::forScene(lit, *volpath);
    ASSERT_TRUE(both);
    EXPECT_EQ(both->colours(), 1u);
    EXPECT_TRUE(both->exactEmission());
}

// The same mean per channel as the spectral film.
TEST(ExactEmission, SameMeanPerChannelAsTheSpectralFilm) {
    const RenderScene scene = glowingBall(true);
    auto volpath = makeVolPathIntegrator();
    test::SpectralFilmVolpath spectral;
    const int n = 16;
    const RenderSettings rs = test::smallRenderSettings(64, 3, n, n);
    const Film exact = render(scene, *volpath, rs, nullptr);
    const Film sampled = render(scene, spectral, rs, nullptr);
    Vec3d meanExact(0.0), meanSampled(0.0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            meanExact += pixelMean(exact.pixel(x, y));
            meanSampled += pixelMean(sampled.pixel(x, y));
        }
    for (int k = 0; k < 3; ++k) {
        ASSERT_GT(meanExact[k], 0.0);
        EXPECT_NEAR(meanSampled[k] / meanExact[k], 1.0, 0.04) << "channel " << k;
    }
}

// A ball glowing at one temperature, filmed exactly: every pixel has the blackbody's
// chromaticity to float rounding, where the spectral film's pixels scatter about it.
TEST(ExactEmission, EveryPixelHasTheBlackbodysChromaticity) {
    RenderScene scene = glowingBall(false);
    auto volpath = makeVolPathIntegrator();
    const Film film = render(scene, *volpath, test::smallRenderSettings(4, 1, 16, 16), nullptr);
    const Vec3 bb = blackbodyXyz(1500.f);
    const double bx = bb.x / (bb.x + bb.y + bb.z), by = bb.y / (bb.x + bb.y + bb.z);
    int lit = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const Vec3d c = pixelMean(film.pixel(x, y));
            const double sum = c.x + c.y + c.z;
            if (!(sum > 0.0)) continue;
            ++lit;
            EXPECT_NEAR(c.x / sum, bx, 1e-5);
            EXPECT_NEAR(c.y / sum, by, 1e-5);
        }
    EXPECT_GT(lit, 50);
}
