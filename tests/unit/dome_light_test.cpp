// The dome light (light/dome_light.h): the image's directions follow its luminance × sin θ (χ²),
// the next-event estimate is unbiased (its mean is ∫ L dω), rotation turns the image, photons
// carry the power that crosses the scene's bounding disc, an HDR file reads back, and a white
// furnace: an albedo-1 medium under a white dome shows the dome's radiance whatever its density.
#include "light/dome_light.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "chi_square.h"
#include "render/integrator.h"
#include "render/lamp_sampling.h"
#include "render/light_lobes.h"
#include "test_support.h"

using namespace mirage;

namespace {

// Working space = XYZ: the sampling tests need a colour pipeline, not a particular one.
const Mat3 kXyz;

// A small map with a dark ground, a graded sky and a "sun" of one bright pixel.
LatLongImage skyImage(int w = 16, int h = 8) {
    LatLongImage img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * h * 3);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            float* p = &img.rgb[3 * (size_t(j) * w + i)];
            const bool sky = j < h / 2;
            p[0] = sky ? 0.3f + 0.05f * i : 0.05f;
            p[1] = sky ? 0.5f + 0.02f * j : 0.04f;
            p[2] = sky ? 1.0f : 0.02f;
        }
    float* sun = &img.rgb[3 * (size_t(1) * w + 5)];
    sun[0] = sun[1] = sun[2] = 200.f;
    return img;
}

// The pixel an image direction falls in, by the convention of dome_light.h (no rotation).
int pixelOf(const Vec3& d, int w, int h) {
    const float theta = std::acos(std::max(-1.f, std::min(1.f, d.y)));
    float phi = std::atan2(-d.x, d.z);
    if (phi < 0) phi += 2 * kPi;
    const int i = std::min(w - 1, int(phi / (2 * kPi) * w));
    const int j = std::min(h - 1, int(theta / kPi * h));
    return j * w + i;
}

// Y of a pixel as the light sees it: its spectrum's luminance.
double pixelLuminance(const LatLongImage& img, int p) {
    const Vec3 rgb(img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]);
    return spectrumToXyz(rgbIlluminantSpectrum(rgb, kXyz)).y;
}

SampledWavelengths fixedWavelengths() {
    SampledWavelengths w;
    w.lambda = {420.f, 510.f, 580.f, 650.f};
    w.pdf = {1.f, 1.f, 1.f, 1.f};
    return w;
}

}  // namespace

TEST(DomeLight, ImageDirectionsFollowLuminanceTimesSinTheta) {
    const LatLongImage img = skyImage();
    auto dome = makeDomeLight(img, 1.f, kXyz, {});
    const int n = img.width * img.height, samples = 400000;
    std::vector<double> observed(n, 0.0), expected(n, 0.0);
    double total = 0.0;
    for (int p = 0; p < n; ++p) {
        const int j = p / img.width;
        expected[p] = pixelLuminance(img, p) * std::sin(kPi * (j + 0.5) / img.height);
        total += expected[p];
    }
    for (double& e : expected) e *= samples / total;
    Sampler s(3, 0, 0);
    const SampledWavelengths w = fixedWavelengths();
    for (int k = 0; k < samples; ++k) {
        float u1 = s.get1D(), u2 = s.get1D();
        LightSample ls;
        ASSERT_TRUE(dome->sampleLi(Vec3(0.f), u1, u2, w, &ls));
        ASSERT_TRUE(std::isinf(ls.distance));
        ASSERT_NEAR(length(ls.wi), 1.f, 1e-5f);
        observed[pixelOf(ls.wi, img.width, img.height)] += 1;
    }
    const test::ChiSquare c = test::chiSquare(observed, expected);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof)) << "dof " << c.dof;
}

TEST(DomeLight, NextEventEstimateIsUnbiased) {
    // E[Li] = ∫ L(ω) dω, which for a map constant over each pixel is Σ L_p ΔΩ_p exactly,
    // ΔΩ_p = 2π/W (cos θ0 − cos θ1).
    const LatLongImage img = skyImage();
    auto dome = makeDomeLight(img, 1.f, kXyz, {});
    const SampledWavelengths w = fixedWavelengths();
    SampledSpectrum reference(0.f);
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i) {
            const double t0 = kPi * j / img.height, t1 = kPi * (j + 1) / img.height;
            const float dOmega = float(2 * kPi / img.width * (std::cos(t0) - std::cos(t1)));
            const float theta = float(kPi * (j + 0.5) / img.height);
            const float phi = float(2 * kPi * (i + 0.5) / img.width);
            const Vec3 d(-std::sin(theta) * std::sin(phi), std::cos(theta),
                         std::sin(theta) * std::cos(phi));
            reference += dome->escapedRadiance(d, w, false) * dOmega;
        }
    const int n = 200000;
    std::vector<double> sum(4, 0.0), sum2(4, 0.0);
    Sampler s(5, 0, 0);
    for (int k = 0; k < n; ++k) {
        float u1 = s.get1D(), u2 = s.get1D();
        LightSample ls;
        if (!dome->sampleLi(Vec3(0.f), u1, u2, w, &ls)) continue;
        for (int c = 0; c < 4; ++c) {
            sum[c] += ls.Li[c];
            sum2[c] += double(ls.Li[c]) * ls.Li[c];
        }
    }
    for (int c = 0; c < 4; ++c) {
        const double mean = sum[c] / n, se = std::sqrt((sum2[c] / n - mean * mean) / n);
        EXPECT_NEAR(mean, reference[c], 4 * se + 1e-4 * reference[c]) << "λ " << w.lambda[c];
    }
}

TEST(DomeLight, ShowsItsPixelsBackAndRotates) {
    LatLongImage img = skyImage();
    auto dome = makeDomeLight(img, 2.f, kXyz, {});
    DomeSettings turned;
    turned.rotationDeg = 90.f;
    auto rotated = makeDomeLight(img, 2.f, kXyz, turned);
    const SampledWavelengths w = fixedWavelengths();
    // The image centre looks along −z; the sun pixel (5, 1) lies at φ = 2π·5.5/16.
    const float theta = kPi * 1.5f / 8, phi = 2 * kPi * 5.5f / 16;
    const Vec3 sun(-std::sin(theta) * std::sin(phi), std::cos(theta),
                   std::sin(theta) * std::cos(phi));
    const SampledSpectrum expected =
        rgbIlluminantSpectrum(Vec3(400.f), kXyz).sample(w);  // 200 × intensity 2
    const SampledSpectrum seen = dome->escapedRadiance(sun, w, true);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(seen[c], expected[c], 1e-3f * expected[c]);
    // Turned by +90° about +y (counter-clockwise from above: −z goes to −x).
    const float c90 = 0.f, s90 = 1.f;
    const Vec3 sunTurned(sun.x * c90 + sun.z * s90, sun.y, -sun.x * s90 + sun.z * c90);
    const SampledSpectrum seenTurned = rotated->escapedRadiance(sunTurned, w, true);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(seenTurned[c], expected[c], 1e-3f * expected[c]);
    // Hidden from the camera, still seen after a bounce.
    DomeSettings hidden;
    hidden.cameraVisible = false;
    auto hiddenDome = makeDomeLight(img, 2.f, kXyz, hidden);
    EXPECT_TRUE(hiddenDome->escapedRadiance(sun, w, true).isZero());
    EXPECT_FALSE(hiddenDome->escapedRadiance(sun, w, false).isZero());
}

TEST(DomeLight, PhotonsCarryThePowerThroughTheBoundingDisc) {
    Bounds3 b;
    b.lo = Vec3(-1.f, 0.f, -2.f);
    b.hi = Vec3(1.f, 2.f, 0.f);
    const float r = 0.5f * length(b.diagonal());
    // Constant white dome L = 1 per nm: Φ = π r² 4π × 470 nm, each photon of weight 1.
    auto white = makeDomeLight(Spectrum(1.f), {});
    EXPECT_NEAR(white->emittedPower(b), kPi * r * r * 4 * kPi * 470.f,
                1e-3 * kPi * r * r * 4 * kPi * 470.f);
    // The image dome: weights of mean 1, photons aimed through the bounding sphere.
    auto dome = makeDomeLight(skyImage(), 1.f, kXyz, {});
    Sampler s(11, 0, 0);
    double sum = 0, sum2 = 0;
    const int n = 200000;
    for (int k = 0; k < n; ++k) {
        PhotonEmission e;
        ASSERT_TRUE(dome->emitPhoton(b, s, &e));
        ASSERT_GE(e.lambda, kLambdaMin);
        ASSERT_LE(e.lambda, kLambdaMax);
        // The photon's line passes within r of the centre and starts outside the sphere.
        const Vec3 oc = b.center() - e.origin;
        const Vec3 closest = oc - e.direction * dot(oc, e.direction);
        ASSERT_LE(length(closest), r * 1.0001f);
        ASSERT_GE(length(oc), r);
        sum += e.weight;
        sum2 += double(e.weight) * e.weight;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0, 4 * se + 1e-3);
}

TEST(DomeLight, ReadsAnHdrFile) {
    const std::string path = test::tempDir() + "/dome.hdr";
    const LatLongImage img = skyImage(8, 4);
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(path, OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeFloat)));
    ASSERT_TRUE(out->write_image(OIIO::TypeFloat, img.rgb.data()));
    out->close();
    const LatLongImage back = readLatLongImage(path);
    ASSERT_EQ(back.width, 8);
    ASSERT_EQ(back.height, 4);
    // RGBE: an 8-bit mantissa per channel over the pixel's largest channel's exponent.
    for (size_t k = 0; k < img.rgb.size(); ++k) {
        const size_t p = k / 3;
        const float largest = std::max({img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]});
        EXPECT_NEAR(back.rgb[k], img.rgb[k], 0.01f * largest) << k;
    }
    EXPECT_THROW(readLatLongImage(test::tempDir() + "/missing.hdr"), MirageError);
    LatLongImage bad = img;
    bad.rgb[4] = std::nanf("");
    EXPECT_THROW(makeDomeLight(bad, 1.f, kXyz, {}), MirageError);
}

namespace {

// The white furnace: volpath's camera rays from 4 m onto the 2 m cube of `scene`'s albedo-1
// medium under its dome, whose radiance (the same from every direction) the medium shows exactly
// at every wavelength, whatever its optical thickness (dL/ds = −σt L + σs ∫ p L dω = 0 when L is
// the dome's everywhere). The mean of the samples' radiance over the dome's at their wavelengths
// is 1.
void expectWhiteFurnace(const RenderScene& scene, uint64_t seed, const std::string& what) {
    auto volpath = makeVolPathIntegrator();
    ThreadState ts(scene);
    test::SampleMean ratio;
    for (int i = 0; i < 20000; ++i) {
        Sampler s(seed, uint64_t(i), 0);
        const SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        const float u1 = s.get1D(), u2 = s.get1D();
        const Vec3 target(0.8f * (2 * u1 - 1), 0.8f * (2 * u2 - 1), 0.f);
        const Vec3 o(0.f, 0.f, 4.f);
        const RadianceSample r =
            volpath->Li(scene, Ray{o, normalize(target - o), kInfinity}, w, s, ts);
        ratio.add(r.L.average() /
                  scene.lights[0]->escapedRadiance(Vec3(0, 1, 0), w, false).average());
    }
    const double mean = ratio.mean(), se = ratio.standardError();
    EXPECT_NEAR(mean, 1.0, 4 * se + 2e-3) << what << " ± " << se;
    EXPECT_EQ(volpath->stats().cappedPaths, 0u) << what;
}

// A scene of the furnace: the dome, then a 2 m cube of unit density, albedo 1.
RenderScene furnaceScene(std::unique_ptr<Light> dome, float sigmaS, float g) {
    RenderScene scene = test::unitCubeScene(sigmaS, g);
    scene.lights.push_back(std::move(dome));
    return scene;
}

// A dome image of one colour: not uniform to the renderer (Light::uniformRadiance), so its
// own samples are drawn too.
LatLongImage oneColourImage() { return test::flatSky(16, 8, 1.f); }

}  // namespace

TEST(DomeLight, WhiteFurnace) {
    for (float sigmaS : {0.5f, 8.f})
        expectWhiteFurnace(furnaceScene(makeDomeLight(Spectrum(1.f), {}), sigmaS, 0.6f), 21,
                           "σs " + std::to_string(sigmaS));
}

// The white furnace again under a dome drawn from an image of one colour, rendered with and
// without the camera ray's points for the dome. Past the camera ray each medium vertex samples
// it by next-event estimation and leaves the phase function's strategy to the path's
// continuation, which scores it where it leaves the medium (render/direct_light.cpp,
// MediumLights::SkyByEscape). A power weight that did not sum to 1 over the two, or an escape
// scored twice, moves the mean off the dome's radiance at each sampled wavelength. Deep in the
// cube shadow rays find no light, and the vertices after them draw the dome's samples at a
// lower rate (render/direct_light.h: SkyDraws): an escape weighed without that rate read 0.91.
TEST(DomeLight, WhiteFurnaceOfAnImageDomeOfOneColour) {
    for (bool skyPoints : {true, false}) {
        RenderScene scene = furnaceScene(makeDomeLight(oneColourImage(), 1.f, kXyz, {}), 8.f, 0.6f);
        ASSERT_FALSE(scene.lights[0]->uniformRadiance());
        scene.equiangular = skyPoints;
        expectWhiteFurnace(scene, 22, skyPoints ? "sky points" : "no sky points");
    }
}

// The white furnace where the camera ray crosses more than kForkDepth of majorant depth (σs 20
// over the 2 m cube: 40), so that its points for the dome weigh against delta tracking's
// scattering point, which leaves the dome to its continuation: the escape carries that
// point's weight (LampSampling::skyWeight). Counted whole, it read 1.0035 (and the furnace
// above, at σs 8, 1.0065).
TEST(DomeLight, WhiteFurnaceOfADenseCubeBehindTheDomePoints) {
    for (bool image : {false, true}) {
        RenderScene scene = furnaceScene(image ? makeDomeLight(oneColourImage(), 1.f, kXyz, {})
                                               : makeDomeLight(Spectrum(1.f), {}),
                                         20.f, 0.6f);
        ASSERT_TRUE(skyPointsFork(scene));
        expectWhiteFurnace(scene, 24, image ? "image" : "constant");
    }
}

// The white furnace of a forward medium (HG g 0.9, past the lobe walks' threshold) with a faint
// lamp for the walks to aim at (render/light_lobes.h): the paths are guided, so each medium
// vertex's estimates, its escape included, carry its share 1/(1 + ratios) against the walks that
// could have drawn it. An escape that kept its whole weight would count those paths twice (the
// mean read 1.064 and 1.049). The walks' vertices leave the image dome to their own escapes,
// which count 1/q of themselves (the walk goes on with probability q): without it, 0.984. The lamp's 10⁻⁶ W adds ~10⁻⁸ to a radiance of 1. Under a constant
// dome and an image of one colour (the two ways a vertex leaves the dome to its escape).
TEST(DomeLight, WhiteFurnaceOfAForwardMediumWithLobeWalks) {
    for (bool image : {false, true}) {
        RenderScene scene = furnaceScene(image ? makeDomeLight(oneColourImage(), 1.f, kXyz, {})
                                               : makeDomeLight(Spectrum(1.f), {}),
                                         4.f, 0.9f);
        scene.lights.push_back(makePointLight(Vec3(0.f, 2.f, 0.f), 1e-6f, Spectrum(1.f)));
        ASSERT_TRUE(guidesPaths(scene));
        expectWhiteFurnace(scene, 23, image ? "image" : "constant");
    }
}

// A sun in the map: the direction of the power within 5° of the brightest pixel, where that
// holds at least half of the dome's (Light::lobe). A bright patch of sky that does not, and a
// constant dome, have none.
TEST(DomeLight, FindsTheSunInAMap) {
    const int w = 512, h = 256;
    LatLongImage img = test::flatSky(w, h, 0.3f);
    // A sun of 3 × 3 pixels about column 300, row 80 (35.2° above the horizon).
    // The pixel's centre by the convention of dome_light.h (pixelOf above, inverted).
    const float theta = kPi * 80.5f / h, phi = 2 * kPi * 300.5f / w;
    const Vec3 expected(-std::sin(theta) * std::sin(phi), std::cos(theta),
                        std::sin(theta) * std::cos(phi));
    const auto paint = [&](float v) {
        for (int j = 79; j <= 81; ++j)
            for (int i = 299; i <= 301; ++i)
                for (int c = 0; c < 3; ++c) img.rgb[3 * (size_t(j) * w + i) + c] = v;
    };
    paint(2e4f);  // 0.86 of the dome's power
    const auto sun = makeDomeLight(img, 1.f, kXyz, DomeSettings{})->lobe();
    ASSERT_TRUE(sun.has_value());
    EXPECT_GT(dot(sun->dir, expected), std::cos(radians(0.3f)));
    EXPECT_GT(sun->irradiance, 0.f);
    paint(2e3f);  // 0.37 of it: a bright patch of sky, not a sun
    EXPECT_FALSE(makeDomeLight(img, 1.f, kXyz, DomeSettings{})->lobe().has_value());
    EXPECT_FALSE(makeDomeLight(Spectrum(1.f), DomeSettings{})->lobe().has_value());
}

// A path cut at its last vertex has no continuation to leave the dome to: there the vertex
// takes the dome by its shadow rays. Volpath cut after one scattering event is then the
// single-scattering integrator (before, under a constant dome, it read 0).
TEST(DomeLight, APathsLastVertexStillSeesTheDome) {
    RenderScene scene = furnaceScene(makeDomeLight(Spectrum(1.f), {}), 2.f, 0.6f);
    scene.equiangular = false;
    const Ray ray{Vec3(-2.f, 0.1f, 0.2f), Vec3(1, 0, 0), kInfinity};
    const auto cut = test::estimateAlongRay(*makeVolPathIntegrator(1), scene, ray, 20000);
    const auto single = test::estimateAlongRay(*makeSingleScatterIntegrator(), scene, ray, 20000);
    EXPECT_GT(single.mean, 0.1);
    EXPECT_NEAR(cut.mean, single.mean, 4 * std::hypot(cut.se, single.se));
}
