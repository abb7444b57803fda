// Colour without chromatic noise (render/achromatic_film.h): taken exactly when nothing in the
// scene is spectral, the same mean as the spectral film per channel, and every pixel exactly
// the light's chromaticity; the photon mapper's photons carry the light's exact colour with the
// same mean flux per channel as photons at their own wavelengths.
#include "render/achromatic_film.h"

#include <gtest/gtest.h>

#include <cmath>

#include "photon/photon_pass.h"
#include "photon/volume_estimate.h"
#include "render/renderer.h"
#include "spectrum/cie.h"
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
    EXPECT_TRUE(AchromaticFilm::forScene(scene, *makePhotonIntegrator(ps)));
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

// Every lit pixel of `film` has the chromaticity of kWarm, to float rounding.
void expectLightsChromaticity(const Film& film) {
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

TEST(AchromaticFilm, EveryPixelHasTheLightsChromaticity) {
    RenderScene scene = greyScene(kWarm);
    auto volpath = makeVolPathIntegrator();
    expectLightsChromaticity(
        render(scene, *volpath, test::smallRenderSettings(4, 3, 16, 16), nullptr));
}

// The photon mapper on a grey scene: the single-scattered part filmed exactly and every photon
// of the light's colour, so no pixel has colour noise (each photon at its own wavelength gave
// blotches of colour).
TEST(AchromaticFilm, EveryPhotonPixelHasTheLightsChromaticity) {
    RenderScene scene = greyScene(kWarm);
    PhotonIntegratorSettings ps;
    ps.photons = 20000;
    ps.progress = Progress::Mode::Quiet;
    auto photon = makePhotonIntegrator(ps);
    photon->preprocess(scene);
    expectLightsChromaticity(
        render(scene, *photon, test::smallRenderSettings(4, 3, 16, 16), nullptr));
    EXPECT_NE(photon->stats().summary.find("photons carry the light's XYZ"), std::string::npos);
}

// A photon's flux is Φ cmf(λ)/∫ȳ at the wavelength its light draws, whose mean is Φ times
// xyzPerWatt (the film's XYZ of S over ∫S dλ): the lights' own draws of λ average to it per
// channel within 4 standard errors of their mean (2·10⁵ draws: ~0.5 %). For a white light Y per
// watt is the closed form 1/470 nm (Y of S = 1 over ∫1 dλ, the trapezoids over 360–830 nm the
// lights sample with). The photon map built with it gives every photon that colour exactly.
TEST(AchromaticFilm, PhotonsCarryTheMeanColourOfTheirWavelengths) {
    for (const Spectrum& colour : {kWarm, Spectrum(1.f)}) {
        RenderScene scene = greyScene(colour);
        const auto achromatic = AchromaticFilm::forScene(scene, *makeVolPathIntegrator());
        ASSERT_TRUE(achromatic);
        const Vec3d perWatt(achromatic->xyzPerWatt());
        const int n = 200000;
        Vec3d sum(0.0), sum2(0.0);
        for (int i = 0; i < n; ++i) {
            Sampler s(3, uint64_t(i), 0);
            PhotonEmission em;
            ASSERT_TRUE(scene.lights[0]->emitPhoton(scene.bounds(), s, &em));
            const Vec3d x = Vec3d(cieXyz(em.lambda)) * double(em.weight / kCieYIntegral);
            sum += x;
            sum2 += x * x;
        }
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[c] / n;
            const double error = std::sqrt((sum2[c] / n - mean * mean) / (n - 1));
            EXPECT_NEAR(mean, perWatt[c], 4.0 * error) << "channel " << c;
        }
        if (colour.isConstant()) {
            EXPECT_NEAR(perWatt.y * 470.0, 1.0, 1e-5);
        }

        PhotonPassSettings pass;
        pass.photons = 2000;
        pass.progress = Progress::Mode::Quiet;
        const std::vector<const Light*> lights{scene.lights[0].get()};
        const PhotonList list = tracePhotons(lights, scene.mediaPointers(), pass, nullptr);
        ASSERT_FALSE(list.empty());
        const VolumePhotons exact(list, scene.mediaPointers(), achromatic->xyzPerWatt());
        for (size_t i = 0; i < exact.size(); ++i) {
            const Vec3 expected = achromatic->xyzPerWatt() * exact.map()[i].power;
            for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(exact.fluxXyz(i)[c], expected[c]);
        }
    }
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
