// Blackbody emission in grey media filmed in its exact colour (render/achromatic_film.h,
// spectrum/blackbody_xyz.h): the table against the film's own sum, the shortcut taken only for
// an integrator that records emission with its temperature, the same mean per channel as the
// spectral film, less noise, and a constant dome counted as a light of one colour.
#include <gtest/gtest.h>

#include <cmath>

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

// A ball of grey smoke whose centre glows at 1800 K, cooling to 600 K at its edge; no light.
RenderScene glowingBall() {
    ShaderDesc s = test::greyShader(2.f, 6.f);
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    s.emission = e;
    std::vector<FloatGrid> grids;
    for (const std::string& slot : s.gridSlots())
        grids.push_back(slot == "temperature"
                            ? test::makeGrid([](int i, int j, int k) { return 600.f + 1200.f * ball(i, j, k); },
                                             0, 23, 1.0 / 24, Vec3d(0.0), "temperature")
                            : test::makeGrid(ball, 0, 23, 1.0 / 24));
    RenderScene scene;
    scene.media.push_back(std::make_unique<Medium>(s, std::move(grids), Transform(), 1.f, 16));
    scene.camera.position = Vec3(0.5f, 0.55f, 3.f);
    scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
    scene.camera.fovDeg = 24.f;
    return scene;
}

// volpath filmed at four wavelengths per sample, as before the shortcut.
class SpectralFilmVolpath : public Integrator {
public:
    const IntegratorInfo& info() const override { return mInner->info(); }
    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        return mInner->Li(scene, ray, w, sampler, ts);
    }

private:
    std::unique_ptr<Integrator> mInner = makeVolPathIntegrator();
};

Vec3d pixelMean(const Film::Pixel& p) {
    return Vec3d(p.xyz[0], p.xyz[1], p.xyz[2]) / double(std::max<uint64_t>(p.samples, 1));
}

}  // namespace

TEST(BlackbodyXyz, MatchesTheFilmsSumOverTemperatures) {
    for (double T : {150.0, 300.0, 650.0, 1000.0, 1500.0, 2700.0, 6500.0, 25000.0, 99000.0,
                     300000.0}) {
        Vec3d sum(0.0);
        for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
            const double l = kLambdaMin + double(i);
            sum += Vec3d(cieXyz(float(l))) * (planck(l, T) * 1e-9);
        }
        sum = sum / double(kCieYIntegral);
        const Vec3 got = blackbodyXyz(float(T));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c] / sum[c], 1.0, 1e-4) << T << " K, " << c;
    }
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
    EXPECT_FALSE(AchromaticFilm::forScene(scene, *makePhotonIntegrator(PhotonIntegratorSettings())));
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

// The same mean per channel as the spectral film, with less noise between two seeds.
TEST(ExactEmission, SameMeanPerChannelLessNoise) {
    const RenderScene scene = glowingBall();
    auto volpath = makeVolPathIntegrator();
    SpectralFilmVolpath spectral;
    const int n = 16;
    auto renderSeed = [&](Integrator& integrator, uint64_t seed) {
        return render(scene, integrator, test::smallRenderSettings(32, seed, n, n), nullptr);
    };
    const Film e1 = renderSeed(*volpath, 1), e2 = renderSeed(*volpath, 2);
    const Film s1 = renderSeed(spectral, 1), s2 = renderSeed(spectral, 2);
    Vec3d meanExact(0.0), meanSpectral(0.0);
    double noiseExact = 0.0, noiseSpectral = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const Vec3d a = pixelMean(e1.pixel(x, y)), b = pixelMean(e2.pixel(x, y));
            const Vec3d c = pixelMean(s1.pixel(x, y)), d = pixelMean(s2.pixel(x, y));
            meanExact += a + b;
            meanSpectral += c + d;
            for (int k = 0; k < 3; ++k) {
                noiseExact += (a[k] - b[k]) * (a[k] - b[k]);
                noiseSpectral += (c[k] - d[k]) * (c[k] - d[k]);
            }
        }
    for (int k = 0; k < 3; ++k) {
        ASSERT_GT(meanExact[k], 0.0);
        EXPECT_NEAR(meanSpectral[k] / meanExact[k], 1.0, 0.03) << "channel " << k;
    }
    std::printf("noise between seeds: exact %.4g, spectral %.4g (%.1f×)\n", noiseExact,
                noiseSpectral, noiseSpectral / noiseExact);
    EXPECT_LT(2.0 * noiseExact, noiseSpectral);
}
