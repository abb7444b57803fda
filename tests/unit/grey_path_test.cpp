// "Model only what a scene requires": a medium whose coefficients do not depend on wavelength
// takes the grey path (medium/medium.h). It must be detected exactly when it applies, give the
// same coefficients as the spectral path, and the same image on a grey scene.
#include <gtest/gtest.h>

#include <cmath>

#include "film/color.h"
#include "render/renderer.h"
#include "test_support.h"

using namespace mirage;

namespace {

auto ball = [](int i, int j, int k) {
    float x = (i - 11.5f) / 12.f, y = (j - 11.5f) / 12.f, z = (k - 11.5f) / 12.f;
    return std::max(0.f, 1.f - (x * x + y * y + z * z));
};

std::unique_ptr<Medium> twoComponentMedium(bool greyPath) {
    ShaderDesc s = test::greyShader(0.3f, 3.f, 0.4f);
    MediumComponent haze;
    haze.name = "haze";
    haze.concentration = 0.5f;  // homogeneous
    haze.sigmaA = Spectrum(0.1f);
    haze.sigmaS = Spectrum(0.6f);
    haze.g = -0.2f;
    s.components.push_back(haze);
    std::vector<FloatGrid> grids{test::makeGrid(ball, 0, 23, 1.0 / 24)};
    auto m = std::make_unique<Medium>(s, std::move(grids), Transform(), 1.f, 16);
    m->setGreyPath(greyPath);
    return m;
}

}  // namespace

TEST(GreyPath, DetectedOnlyWhenEveryCoefficientIsWavelengthIndependent) {
    EXPECT_TRUE(twoComponentMedium(true)->greyCoefficients());
    EXPECT_TRUE(twoComponentMedium(true)->greyPath());
    EXPECT_FALSE(twoComponentMedium(false)->greyPath());

    ShaderDesc tinted = test::greyShader(0.3f, 3.f);
    tinted.components[0].sigmaS = Spectrum::fromTable({400.f, 700.f}, {3.f, 1.f});
    Medium spectral(tinted, {test::makeGrid(ball, 0, 23, 1.0 / 24)}, Transform(), 1.f, 16);
    EXPECT_FALSE(spectral.greyCoefficients());

    ShaderDesc glowing = test::greyShader(0.3f, 3.f);
    glowing.components[0].quantumEfficiency = 0.1f;
    Medium fluorescent(glowing, {test::makeGrid(ball, 0, 23, 1.0 / 24)}, Transform(), 1.f, 16);
    EXPECT_FALSE(fluorescent.greyCoefficients());
}

TEST(GreyPath, SameCoefficientsAsTheSpectralPath) {
    auto grey = twoComponentMedium(true), spectral = twoComponentMedium(false);
    Medium::Context cg(*grey), cs(*spectral);
    Sampler sampler(3, 0, 0);
    for (int n = 0; n < 1000; ++n) {
        SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
        cg.setWavelengths(w);
        cs.setWavelengths(w);
        Vec3 p(sampler.get1D(), sampler.get1D(), sampler.get1D());
        MediumPoint a, b;
        grey->eval(p, cg, &a);
        spectral->eval(p, cs, &b);
        for (int i = 0; i < kSpectrumSamples; ++i) {
            ASSERT_FLOAT_EQ(a.sigmaA[i], b.sigmaA[i]);
            ASSERT_FLOAT_EQ(a.sigmaS[i], b.sigmaS[i]);
            ASSERT_FLOAT_EQ(a.sigmaSComponent[1][i], b.sigmaSComponent[1][i]);
        }
        // The photon estimates' σs at one wavelength (Medium::sigmaSAt) takes the grey path too.
        ASSERT_FLOAT_EQ(grey->sigmaSAt(p, cg, w.lambda[0]), spectral->sigmaSAt(p, cs, w.lambda[0]));
        ASSERT_FLOAT_EQ(grey->sigmaSAt(p, cg, w.lambda[0]), a.sigmaS[0]);
        EXPECT_EQ(cg.wavelengths().lambda[0], w.lambda[0]);  // the path's λ still recorded
    }
}

TEST(GreyPath, SameImageAsTheSpectralPath) {
    ColorPipeline color;
    Image images[2];
    for (int spectralPath = 0; spectralPath < 2; ++spectralPath) {
        RenderScene scene;
        scene.media.push_back(twoComponentMedium(spectralPath == 0));
        scene.lights.push_back(makeDistantLight(normalize(Vec3(0.3f, -1.f, -0.2f)), 1000.f,
                                                blackbodyNormalized(5800.f)));
        scene.camera.position = Vec3(0.5f, 0.55f, 3.f);
        scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
        scene.camera.fovDeg = 24.f;
        RenderSettings rs;
        rs.width = rs.height = 24;
        rs.tileSize = 8;
        rs.spp = 16;
        rs.seed = 9;
        rs.progress = Progress::Mode::Quiet;
        auto volpath = makeVolPathIntegrator();
        images[spectralPath] = render(scene, *volpath, rs, nullptr).develop(color);
    }
    // Same random numbers, same coefficients: the images agree far below their noise
    // (16 spp: several % per pixel).
    double sum = 0.0, maxDiff = 0.0;
    for (size_t i = 0; i < images[0].rgba.size(); ++i) {
        sum += images[1].rgba[i];
        maxDiff = std::max(maxDiff, double(std::abs(images[0].rgba[i] - images[1].rgba[i])));
    }
    const double mean = sum / double(images[0].rgba.size());
    ASSERT_GT(mean, 0.0);
    EXPECT_LT(maxDiff, 1e-4 * mean);
}
