// Emissive media as a light (render/emission_light.h, render/line_emission.h): the directions
// drawn towards the coarse power grid follow the density p_L that the 3D-DDA sums (Pearson's χ²
// on an equal-area grid of the sphere, and ∫ p_L dω = 1), from outside and from inside a
// rotated, unevenly scaled volume; the distances drawn along a line follow theirs (χ² again,
// with the line sample's floor and without, one volume and two overlapping); and the line
// estimate's mean is ∫ T σa Le dt in closed form
// through an isothermal, homogeneous block.
#include "render/emission_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chi_square.h"
#include "render/line_emission.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr int kN = 24;
constexpr double kH = 1.0 / kN;

// A glowing medium: one grey component on slot "density", emission at slot "temperature".
std::unique_ptr<Medium> glowingMedium(const std::function<float(int, int, int)>& density,
                                      const std::function<float(int, int, int)>& kelvin,
                                      float sigmaA, float sigmaS, const Transform& xf) {
    std::vector<FloatGrid> grids;
    grids.push_back(test::makeGrid(density, 0, kN - 1, kH));
    grids.push_back(test::makeGrid(kelvin, 0, kN - 1, kH, Vec3d(0.0), "temperature"));
    return std::make_unique<Medium>(test::glowingShader(sigmaA, sigmaS, 0.3f), std::move(grids), xf,
                                    1.f, 16);
}

// Two flames of unequal heat in a box of smoke, rotated 30° about z and stretched along y.
RenderScene twoFlames() {
    auto kelvin = [](int i, int j, int k) {
        auto blob = [&](double ci, double cj, double ck, double r, double T) {
            const double d2 = (i - ci) * (i - ci) + (j - cj) * (j - cj) + (k - ck) * (k - ck);
            return T * std::exp(-d2 / (r * r));
        };
        return float(300.0 + blob(6, 5, 8, 3, 1500) + blob(17, 8, 15, 2.5, 1200));
    };
    RenderScene scene;
    const Transform xf =
        Transform::rotate(30.0, Vec3d(0, 0, 1)) * Transform::scale(Vec3d(1, 1.5, 1));
    scene.media.push_back(glowingMedium([](int, int, int) { return 1.f; }, kelvin, 0.5f, 2.f, xf));
    return scene;
}

// χ² of draws from x against p_L, and ∫ p_L dω (test::sphereChiSquare, kSub² sub-cells a bin).
template <int kSub>
void checkDirections(const RenderScene& scene, const Vec3& x) {
    const auto light = EmissionLight::forScene(scene);
    ASSERT_TRUE(light);
    ThreadState ts(scene);
    ts.tracking.setWavelengths(SampledWavelengths::sampleVisible(0.4f));
    Sampler s(5, 0, 0);
    bool drawn = true, same = true;
    const test::SphereChiSquare c = test::sphereChiSquare<30, 60, kSub>(
        300000,
        [&] {
            Vec3 wi;
            float pdf;
            drawn = drawn && light->sample(x, ts.tracking, s, &wi, &pdf);
            same = same && std::abs(pdf - light->pdf(x, wi, ts.tracking)) <= 1e-4f * pdf;
            return wi;
        },
        [&](double dx, double dy, double dz) {
            return light->pdf(x, Vec3(float(dx), float(dy), float(dz)), ts.tracking);
        });
    std::printf("from (%.2f, %.2f, %.2f): ∫ p_L dω = %.4f, χ² %.1f on %d degrees of freedom\n", x.x,
                x.y, x.z, c.integral, c.fit.statistic, c.fit.dof);
    EXPECT_TRUE(drawn);
    EXPECT_TRUE(same);  // the density a draw reports is the one p_L gives its direction
    EXPECT_NEAR(c.integral, 1.0, 0.005);
    EXPECT_LT(c.fit.statistic, test::chiSquareCritical(c.fit.dof));
}

// χ² of distances drawn along ray over (0, tEnd) against distancePdf in 64 equal bins (its
// integral over each by the midpoint rule on 100 sub-steps), ∫ pdf dt = 1, and the density a
// draw reports is distancePdf's at its point; with the line sample's floor and without.
void checkDistances(const RenderScene& scene, const Ray& ray, float tEnd) {
    const auto light = EmissionLight::forScene(scene);
    ASSERT_TRUE(light);
    ThreadState ts(scene);
    ts.tracking.setWavelengths(SampledWavelengths::sampleVisible(0.4f));
    for (const bool floor : {true, false}) {
        constexpr int kBins = 64, kSub = 100, kDraws = 200000;
        std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
        Sampler s(4, 0, 0);
        float mass = 0.f;
        int drawn = 0, other = 0;
        for (int i = 0; i < kDraws; ++i) {
            EmissionLight::LinePoint p;
            if (!light->sampleDistance(ray, tEnd, ts.tracking, s.get1D(), floor, &p)) continue;
            ++drawn;
            mass = p.mass;
            // A point that rounding puts on a cell's face may read the neighbour's density.
            if (std::abs(p.pdf - light->distancePdf(ray, p.t, p.mass, floor, ts.tracking)) >
                1e-4f * p.pdf)
                ++other;
            observed[size_t(std::min(int(p.t / tEnd * kBins), kBins - 1))] += 1.0;
        }
        ASSERT_EQ(drawn, kDraws);
        double integral = 0.0;
        for (int b = 0; b < kBins; ++b)
            for (int k = 0; k < kSub; ++k) {
                const float t = (float(b) + (float(k) + 0.5f) / kSub) * tEnd / kBins;
                const double p = double(light->distancePdf(ray, t, mass, floor, ts.tracking)) *
                                 tEnd / (kBins * kSub);
                expected[size_t(b)] += p * kDraws;
                integral += p;
            }
        const test::ChiSquare fit = test::chiSquare(observed, expected);
        std::printf("floor %d: ∫ p dt = %.4f, χ² %.1f on %d degrees of freedom, %d of %d draws "
                    "off their density\n",
                    int(floor), integral, fit.statistic, fit.dof, other, drawn);
        EXPECT_NEAR(integral, 1.0, 0.01);
        EXPECT_LT(fit.statistic, test::chiSquareCritical(fit.dof));
        EXPECT_LE(other, kDraws / 10000);
    }
}

}  // namespace

TEST(EmissionLight, DirectionsFollowTheirDensityChiSquare) {
    const RenderScene scene = twoFlames();
    checkDirections<24>(scene, Vec3(1.0f, 0.9f, 1.4f));  // outside the volume
    checkDirections<6>(scene, Vec3(0.1f, 0.6f, 0.45f));  // inside it, beside both flames
}

// Along a line through both flames of the rotated, stretched volume, and through the same
// volume overlapped by a second one shifted along x (where both glow, their densities add).
TEST(EmissionLight, DistancesFollowTheirDensityChiSquare) {
    RenderScene scene = twoFlames();
    const Transform xf =
        Transform::rotate(30.0, Vec3d(0, 0, 1)) * Transform::scale(Vec3d(1, 1.5, 1));
    const Vec3 a = xf.point(Vec3(0.25f, 0.21f, 0.33f)), b = xf.point(Vec3(0.71f, 0.33f, 0.625f));
    const Ray ray{a - (b - a), normalize(b - a), kInfinity};
    checkDistances(scene, ray, 3.f * length(b - a));
    scene.media.push_back(glowingMedium(
        [](int, int, int) { return 1.f; },
        [](int i, int j, int k) {
            const double d2 = (i - 12) * (i - 12) + (j - 8) * (j - 8) + (k - 10) * (k - 10);
            return float(300.0 + 1400.0 * std::exp(-d2 / 16.0));
        },
        0.5f, 2.f, Transform::translate(Vec3d(0.3, 0.1, 0.0)) * xf));
    checkDistances(scene, ray, 3.f * length(b - a));
}

// Cold media emit nothing: no grid, no light.
TEST(EmissionLight, NoneWhereNothingGlows) {
    RenderScene scene;
    scene.media.push_back(glowingMedium([](int, int, int) { return 1.f; },
                                        [](int, int, int) { return 300.f; }, 0.5f, 2.f,
                                        Transform()));
    EXPECT_FALSE(EmissionLight::forScene(scene));
    scene.media[0] = test::gridMedium([](int, int, int) { return 1.f; }, 0, 7, 0.1, 0.5f, 2.f);
    EXPECT_FALSE(EmissionLight::forScene(scene));
}

// The line estimate through an isothermal, homogeneous block of length L along the
// ray: E[L̂] = σa B(λ, T) (1 − e^{−σt L}) / σt per wavelength (grid lookups are trilinear, so
// the ray runs through the block's interior, away from the zero values beyond its last voxel).
TEST(LineEstimate, ThroughAnIsothermalBlockMatchesTheClosedForm) {
    const float sigmaA = 1.5f, sigmaS = 2.5f, T = 1600.f;
    RenderScene scene;
    scene.media.push_back(glowingMedium([](int, int, int) { return 1.f; },
                                        [T](int, int, int) { return T; }, sigmaA, sigmaS,
                                        Transform()));
    const auto light = EmissionLight::forScene(scene);
    ASSERT_TRUE(light);
    ThreadState ts(scene);
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.37f);
    ts.tracking.setWavelengths(w);
    // Voxel centres lie at i h: the fields are constant over [0, (kN − 1) h] along x.
    const float c = float(0.25 * kH), len = float((kN - 1.5) * kH);
    const Ray ray{Vec3(c, 0.5f, 0.5f), Vec3(1.f, 0.f, 0.f), kInfinity};
    constexpr int kRuns = 200000;
    std::array<double, kSpectrumSamples> sum{}, sum2{};
    for (int i = 0; i < kRuns; ++i) {
        Sampler s(9, uint64_t(i), 0);
        RadianceSample out;
        PathRecorder rec(&out, ts);
        const SampledSpectrum L =
            recordLineEmission(*light, ts.tracking, ray, len, SampledSpectrum(1.f), s, rec);
        for (int k = 0; k < kSpectrumSamples; ++k) {
            EXPECT_EQ(L[k], out.L[k]);  // what it returns is what it recorded
            sum[k] += L[k];
            sum2[k] += double(L[k]) * L[k];
        }
    }
    const double sigmaT = sigmaA + sigmaS;
    for (int k = 0; k < kSpectrumSamples; ++k) {
        const double expected = sigmaA * planck(double(w.lambda[k]), double(T)) * 1e-9 *
                                (1.0 - std::exp(-sigmaT * len)) / sigmaT;
        const double mean = sum[k] / kRuns;
        const double se = std::sqrt((sum2[k] / kRuns - mean * mean) / kRuns);
        std::printf("λ %.0f nm: line estimate %.5g ± %.2g, closed form %.5g\n", w.lambda[k], mean,
                    se, expected);
        EXPECT_NEAR(mean, expected, 4.0 * se + 1e-4 * expected);
    }
}
