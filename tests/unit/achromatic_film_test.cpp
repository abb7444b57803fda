// Colour without chromatic noise (render/achromatic_film.h): taken exactly when nothing in the
// scene is spectral, the same mean as the spectral film per channel, and every pixel exactly
// the light's chromaticity.
#include "render/achromatic_film.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "test_support.h"

using namespace mirage;

namespace {

auto ball = [](int i, int j, int k) {
    float x = (i - 11.5f) / 12.f, y = (j - 11.5f) / 12.f, z = (k - 11.5f) / 12.f;
    return std::max(0.f, 1.f - (x * x + y * y + z * z));
};

const Spectrum kWarm = blackbodyNormalized(3200.f);

RenderScene greyScene(const Spectrum& lightColour) {
    RenderScene scene;
    scene.media.push_back(test::gridMedium(ball, 0, 23, 1.0 / 24, 0.4f, 4.f));
    scene.lights.push_back(
        makeDistantLight(normalize(Vec3(0.3f, -1.f, -0.2f)), 1000.f, lightColour));
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

Vec3d meanXyz(const Film& film) {
    Vec3d sum(0.0);
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Film::Pixel& p = film.pixel(x, y);
            sum += Vec3d(p.xyz[0], p.xyz[1], p.xyz[2]) / double(p.samples);
        }
    return sum / double(film.width() * film.height());
}

}  // namespace

TEST(AchromaticFilm, TakenOnlyWhenNothingIsSpectral) {
    auto volpath = makeVolPathIntegrator(), single = makeSingleScatterIntegrator();
    RenderScene scene = greyScene(kWarm);
    EXPECT_TRUE(AchromaticFilm::forScene(scene, *volpath));
    EXPECT_TRUE(AchromaticFilm::forScene(scene, *single));
    // The same colour at another power: still one shape.
    scene.lights.push_back(makePointLight(Vec3(0.5f, 2.f, 0.5f), 50.f, kWarm));
    EXPECT_TRUE(AchromaticFilm::forScene(scene, *volpath));

    PhotonIntegratorSettings ps;
    EXPECT_FALSE(AchromaticFilm::forScene(scene, *makePhotonIntegrator(ps)));
    EXPECT_FALSE(AchromaticFilm::forScene(scene, SpectralFilmVolpath()));

    RenderScene twoColours = greyScene(kWarm);
    twoColours.lights.push_back(
        makePointLight(Vec3(0.5f, 2.f, 0.5f), 50.f, blackbodyNormalized(9000.f)));
    EXPECT_FALSE(AchromaticFilm::forScene(twoColours, *volpath));

    // A light with no power over part of the visible range: G is not readable at every λ.
    RenderScene narrow = greyScene(Spectrum::fromTable({500.f, 510.f, 520.f}, {0.f, 1.f, 0.f}));
    EXPECT_FALSE(AchromaticFilm::forScene(narrow, *volpath));

    RenderScene tinted = greyScene(kWarm);
    ShaderDesc s = test::greyShader(0.4f, 4.f);
    s.components[0].sigmaS = Spectrum::fromTable({400.f, 700.f}, {5.f, 3.f});
    tinted.media[0] = std::make_unique<Medium>(
        s, std::vector<FloatGrid>{test::makeGrid(ball, 0, 23, 1.0 / 24)}, Transform(), 1.f, 16);
    EXPECT_FALSE(AchromaticFilm::forScene(tinted, *volpath));
    std::string why;
    EXPECT_TRUE(sampledColour(tinted, &why));
    EXPECT_NE(why.find("spectral"), std::string::npos);
    EXPECT_FALSE(sampledColour(scene, &why));
}

TEST(AchromaticFilm, EveryPixelHasTheLightsChromaticity) {
    RenderScene scene = greyScene(kWarm);
    auto volpath = makeVolPathIntegrator();
    const Film film = render(scene, *volpath, test::smallRenderSettings(4, 3, 16, 16), nullptr);
    const Vec3d light = spectrumToXyz(kWarm);
    const double lx = light.x / (light.x + light.y + light.z);
    const double ly = light.y / (light.x + light.y + light.z);
    int lit = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Film::Pixel& p = film.pixel(x, y);
            const double sum = p.xyz[0] + p.xyz[1] + p.xyz[2];
            if (!(sum > 0.0)) continue;
            ++lit;
            EXPECT_NEAR(p.xyz[0] / sum, lx, 1e-5);
            EXPECT_NEAR(p.xyz[1] / sum, ly, 1e-5);
        }
    EXPECT_GT(lit, 50);
}

// The shortcut is the expectation over the wavelengths of what the spectral film adds: the
// image means agree per channel within the spectral film's own noise, and its pixels are
// closer to a converged image.
TEST(AchromaticFilm, SameMeanPerChannelAsTheSpectralFilm) {
    RenderScene scene = greyScene(kWarm);
    auto volpath = makeVolPathIntegrator();
    const RenderSettings rs = test::smallRenderSettings(64, 5, 16, 16);
    const Vec3d exact = meanXyz(render(scene, *volpath, rs, nullptr));
    SpectralFilmVolpath spectralFilm;
    const Vec3d spectral = meanXyz(render(scene, spectralFilm, rs, nullptr));
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(exact[c], 0.0);
        EXPECT_NEAR(spectral[c] / exact[c], 1.0, 0.02) << "channel " << c;
    }
}
