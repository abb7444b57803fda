// Colour without chromatic noise (render/achromatic_film.h): taken exactly when nothing in the
// scene is spectral, the same mean as the spectral film per channel, and every pixel exactly
// the light's chromaticity; the photon mapper's photons carry the light's exact colour with the
// same mean flux per channel as photons at their own wavelengths; an image dome is filmed as
// its three basis colours.
#include "render/achromatic_film.h"

#include <gtest/gtest.h>

#include <cmath>

#include "light/dome_light.h"
#include "photon/photon_pass.h"
#include "photon/volume_estimate.h"
#include "render/photon_integrator.h"
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

Vec3d meanXyz(const Film& film) {
    Vec3d sum(0.0);
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Film::Pixel& p = film.pixel(x, y);
            sum += Vec3d(p.xyz[0], p.xyz[1], p.xyz[2]) / double(p.samples);
        }
    return sum / double(film.width() * film.height());
}

// The image means of `volpath` (the shortcut where the scene allows it) and of the spectral
// film agree per channel, within the spectral film's own noise.
void expectTheSpectralFilmsMean(const RenderScene& scene, Integrator& volpath) {
    const RenderSettings rs = test::smallRenderSettings(64, 5, 16, 16);
    const Vec3d exact = meanXyz(render(scene, volpath, rs, nullptr));
    test::SpectralFilmVolpath spectralFilm;
    const Vec3d spectral = meanXyz(render(scene, spectralFilm, rs, nullptr));
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(exact[c], 0.0);
        EXPECT_NEAR(spectral[c] / exact[c], 1.0, 0.02) << "channel " << c;
    }
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
    EXPECT_FALSE(AchromaticFilm::forScene(scene, test::SpectralFilmVolpath()));

    // Lights of two colours: each sample's radiance is split by colour (up to 3 colours).
    RenderScene twoColours = greyScene(kWarm);
    twoColours.lights.push_back(
        makePointLight(Vec3(0.5f, 2.f, 0.5f), 50.f, blackbodyNormalized(9000.f)));
    const auto two = AchromaticFilm::forScene(twoColours, *volpath);
    ASSERT_TRUE(two);
    EXPECT_EQ(two->colours(), 2u);
    EXPECT_EQ(AchromaticFilm::forScene(scene, *volpath)->colours(), 1u);
    twoColours.lights.push_back(makePointLight(Vec3(0.5f, 2.f, 0.f), 50.f, kWarm));
    EXPECT_EQ(AchromaticFilm::forScene(twoColours, *volpath)->colours(), 2u);
    RenderScene fourColours = greyScene(kWarm);
    for (float kelvin : {2000.f, 6500.f, 12000.f})
        fourColours.lights.push_back(
            makePointLight(Vec3(0.5f, 2.f, 0.5f), 50.f, blackbodyNormalized(kelvin)));
    EXPECT_FALSE(AchromaticFilm::forScene(fourColours, *volpath));
    std::string why;
    EXPECT_TRUE(sampledColour(fourColours, integratorInfo("volpath"), &why));
    EXPECT_NE(why.find("more than 3 colours"), std::string::npos) << why;
    EXPECT_FALSE(sampledColour(twoColours, integratorInfo("volpath"), &why));
    EXPECT_NE(why.find("2 light colours"), std::string::npos) << why;

    // A light with no power over part of the visible range: G is not readable at every λ.
    RenderScene narrow = greyScene(Spectrum::fromTable({500.f, 510.f, 520.f}, {0.f, 1.f, 0.f}));
    EXPECT_FALSE(AchromaticFilm::forScene(narrow, *volpath));

    RenderScene tinted = greyScene(kWarm);
    ShaderDesc s = test::greyShader(0.4f, 4.f);
    s.components[0].sigmaS = Spectrum::fromTable({400.f, 700.f}, {5.f, 3.f});
    tinted.media[0] = std::make_unique<Medium>(
        s, std::vector<FloatGrid>{test::makeGrid(ball, 0, 23, 1.0 / 24)}, Transform(), 1.f, 16);
    EXPECT_FALSE(AchromaticFilm::forScene(tinted, *volpath));
    EXPECT_TRUE(sampledColour(tinted, integratorInfo("volpath"), &why));
    EXPECT_NE(why.find("spectral"), std::string::npos);
    EXPECT_FALSE(sampledColour(scene, integratorInfo("volpath"), &why));
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
        const Vec3d perWatt(achromatic->xyzPerWatt(0));
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
        const VolumePhotons exact(list, scene.mediaPointers(), achromatic->xyzPerWattOfLights());
        for (size_t i = 0; i < exact.size(); ++i) {
            const Vec3 expected = achromatic->xyzPerWatt(0) * exact.map()[i].power;
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
    expectTheSpectralFilmsMean(scene, *volpath);
}

// Two light colours (render/achromatic_film.h): a sample's radiance L(λ) = a S1(λ) + b S2(λ) at
// any four wavelengths is filmed as exactly a XYZ[S1] + b XYZ[S2]; with b = 0 it has light 1's
// chromaticity exactly. Three colours likewise.
TEST(AchromaticFilm, SplitsEachSampleByLightColourExactly) {
    const Spectrum shapes[3] = {kWarm, Spectrum::fromTable({360.f, 830.f}, {0.2f, 1.f}),
                                blackbodyNormalized(9000.f)};
    auto volpath = makeVolPathIntegrator();
    for (size_t n : {2u, 3u}) {
        RenderScene s = greyScene(kWarm);
        for (size_t k = 1; k < n; ++k)
            s.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), 1.f, shapes[k]));
        const auto film = AchromaticFilm::forScene(s, *volpath);
        ASSERT_TRUE(film);
        ASSERT_EQ(film->colours(), n);
        for (int draw = 0; draw < 1000; ++draw) {
            Sampler sampler(7, uint64_t(draw), 0);
            const SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
            double weight[3];
            Vec3d expected(0.0);
            RadianceSample rs;
            rs.L = SampledSpectrum(0.f);
            for (size_t k = 0; k < n; ++k) {
                // Light 1 alone in every fourth draw.
                weight[k] = k == 0 || draw % 4 ? 0.1 + 10.0 * sampler.get1D() : 0.0;
                const Spectrum& S = *s.lights[k]->spectrum();
                rs.L += S.sample(w) * float(weight[k]);
                expected += spectrumToXyz(S) * weight[k];
            }
            film->apply(w, &rs);
            EXPECT_TRUE(rs.L.isZero());
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(rs.xyz[c] / expected[c], 1.0, 1e-4) << "draw " << draw << " c " << c;
            if (draw % 4 == 0) {
                const Vec3d one = spectrumToXyz(*s.lights[0]->spectrum());
                const double sum = rs.xyz[0] + rs.xyz[1] + rs.xyz[2];
                EXPECT_NEAR(rs.xyz[0] / sum, one.x / (one.x + one.y + one.z), 1e-5);
                EXPECT_NEAR(rs.xyz[1] / sum, one.y / (one.x + one.y + one.z), 1e-5);
            }
        }
    }
}

// Two spot lights of different colours, each lighting its own vertical column of the ball,
// single scattering: a pixel sees one column, so each lit pixel has the chromaticity of one
// light exactly (its samples' radiance, split by colour, has no part of the other), and both
// colours appear.
TEST(AchromaticFilm, PixelLitByOneLightHasItsChromaticity) {
    const Spectrum kBlue = blackbodyNormalized(12000.f);
    RenderScene scene = greyScene(kWarm);
    scene.lights.clear();
    scene.lights.push_back(
        makeSpotLight(Vec3(0.3f, 6.f, 0.5f), Vec3(0.f, -1.f, 0.f), 50.f, 0.8f, 1.f, kWarm));
    scene.lights.push_back(
        makeSpotLight(Vec3(0.7f, 6.f, 0.5f), Vec3(0.f, -1.f, 0.f), 50.f, 0.8f, 1.f, kBlue));
    auto single = makeSingleScatterIntegrator();
    ASSERT_EQ(AchromaticFilm::forScene(scene, *single)->colours(), 2u);
    const Film film = render(scene, *single, test::smallRenderSettings(4, 3, 24, 24), nullptr);
    auto chromaticity = [](const Vec3d& c) {
        return Vec3d(c.x / (c.x + c.y + c.z), c.y / (c.x + c.y + c.z), 0.0);
    };
    const Vec3d warm = chromaticity(spectrumToXyz(kWarm)),
                blue = chromaticity(spectrumToXyz(kBlue));
    int warmPixels = 0, bluePixels = 0;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Film::Pixel& p = film.pixel(x, y);
            const Vec3d c(p.xyz[0], p.xyz[1], p.xyz[2]);
            if (!(c.x + c.y + c.z > 0.0)) continue;
            const Vec3d xy = chromaticity(c);
            const bool isWarm = std::abs(xy.x - warm.x) < 1e-5 && std::abs(xy.y - warm.y) < 1e-5;
            const bool isBlue = std::abs(xy.x - blue.x) < 1e-5 && std::abs(xy.y - blue.y) < 1e-5;
            EXPECT_TRUE(isWarm || isBlue) << x << "," << y << ": " << xy.x << " " << xy.y;
            warmPixels += isWarm;
            bluePixels += isBlue;
        }
    EXPECT_GT(warmPixels, 10);
    EXPECT_GT(bluePixels, 10);
}

// Two lights of different colours: the image's XYZ per channel is the sum of the two single-
// light renders' and the spectral film's, within their noise (2 %), volpath at 128 samples (at
// 64 the sum's ratio spread 0.991–1.022 over four seeds).
TEST(AchromaticFilm, TwoColoursSumTheSingleLightRenders) {
    const Spectrum kBlue = blackbodyNormalized(12000.f);
    RenderScene both = greyScene(kWarm);
    both.lights.push_back(makeDistantLight(normalize(Vec3(-0.5f, -0.3f, -0.4f)), 600.f, kBlue));
    RenderScene warmOnly = greyScene(kWarm);
    RenderScene blueOnly = greyScene(kWarm);
    blueOnly.lights[0] = makeDistantLight(normalize(Vec3(-0.5f, -0.3f, -0.4f)), 600.f, kBlue);
    auto volpath = makeVolPathIntegrator();
    ASSERT_EQ(AchromaticFilm::forScene(both, *volpath)->colours(), 2u);
    const RenderSettings rs = test::smallRenderSettings(128, 5, 16, 16);
    const Vec3d exact = meanXyz(render(both, *volpath, rs, nullptr));
    const Vec3d sum = meanXyz(render(warmOnly, *volpath, rs, nullptr)) +
                      meanXyz(render(blueOnly, *volpath, rs, nullptr));
    test::SpectralFilmVolpath spectralFilm;
    const Vec3d spectral = meanXyz(render(both, spectralFilm, rs, nullptr));
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(exact[c], 0.0);
        EXPECT_NEAR(sum[c] / exact[c], 1.0, 0.02) << "channel " << c;
        EXPECT_NEAR(spectral[c] / exact[c], 1.0, 0.02) << "channel " << c;
    }
}

// Photons of two lights of different colours each carry their own light's XYZ per watt.
TEST(AchromaticFilm, EachPhotonCarriesItsLightsColour) {
    RenderScene scene = greyScene(kWarm);
    scene.lights.push_back(makeDistantLight(normalize(Vec3(-0.5f, -0.3f, -0.4f)), 600.f,
                                            blackbodyNormalized(12000.f)));
    const auto achromatic = AchromaticFilm::forScene(scene, *makeVolPathIntegrator());
    ASSERT_TRUE(achromatic);
    const Vec3 warm = achromatic->xyzPerWatt(0), blue = achromatic->xyzPerWatt(1);
    EXPECT_GT(warm.x / warm.z, 2.f * blue.x / blue.z);  // two different colours
    PhotonPassSettings pass;
    pass.photons = 4000;
    pass.progress = Progress::Mode::Quiet;
    const std::vector<const Light*> lights{scene.lights[0].get(), scene.lights[1].get()};
    const PhotonList list = tracePhotons(lights, scene.mediaPointers(), pass, nullptr);
    const VolumePhotons exact(list, scene.mediaPointers(), achromatic->xyzPerWattOfLights());
    int of[2] = {0, 0};
    for (size_t i = 0; i < exact.size(); ++i) {
        const uint32_t light = exact.map()[i].light;
        ASSERT_LT(light, 2u);
        ++of[light];
        const Vec3 expected = achromatic->xyzPerWatt(light) * exact.map()[i].power;
        for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(exact.fluxXyz(i)[c], expected[c]);
    }
    EXPECT_GT(of[0], 100);
    EXPECT_GT(of[1], 100);
}

// An image dome (light/dome_light.cpp) sends Σ_k c_k(ω) B_k(λ): three fixed shapes whatever its
// pixels, so a grey medium under it is filmed by colour like three lights, with the spectral
// film's mean per channel. Its photons each have their pixel's colour, not one per light: the
// photon mapper samples colour.
TEST(AchromaticFilm, AnImageDomeIsThreeColours) {
    LatLongImage sky;
    sky.width = 8;
    sky.height = 4;
    for (int j = 0; j < sky.height; ++j)
        for (int i = 0; i < sky.width; ++i)
            sky.rgb.insert(sky.rgb.end(), {j < 2 ? 0.3f : 1.2f, 0.6f, j < 2 ? 1.5f : 0.2f});
    RenderScene scene = greyScene(kWarm);
    scene.lights.clear();
    scene.lights.push_back(makeDomeLight(sky, 2.f, Mat3(), DomeSettings()));
    auto volpath = makeVolPathIntegrator();
    const auto film = AchromaticFilm::forScene(scene, *volpath);
    ASSERT_TRUE(film);
    EXPECT_EQ(film->colours(), 3u);
    std::string why;
    EXPECT_FALSE(sampledColour(scene, integratorInfo("volpath"), &why));
    EXPECT_NE(why.find("3 light colours"), std::string::npos) << why;
    PhotonIntegratorSettings ps;
    EXPECT_FALSE(AchromaticFilm::forScene(scene, *makePhotonIntegrator(ps)));
    EXPECT_TRUE(sampledColour(scene, integratorInfo("photon"), &why));
    EXPECT_NE(why.find("image dome"), std::string::npos) << why;

    expectTheSpectralFilmsMean(scene, *volpath);
}
