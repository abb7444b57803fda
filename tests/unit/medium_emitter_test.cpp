// Photon emission from emissive media (photon/medium_emitter.h), against closed forms:
//  - an isothermal, homogeneous block of voxels emits Φ = 4π σa V ∫ Le dλ (Kirchhoff), with the
//    Planck integral taken here by Simpson's rule at 0.05 nm, independently of the emitter;
//  - in such a block the emitted wavelengths follow Planck's law (χ² test);
//  - in a hot, uneven blob the emitter's estimate Φ_table × mean weight equals the integral of
//    the emission field by fine quadrature over the grid (the weights make it unbiased).
#include "photon/medium_emitter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "photon/photon_pass.h"
#include "test_support.h"

using namespace mirage;

namespace {

// ∫_a^b B(λ,T) dλ per nm (W·m⁻²·sr⁻¹), Simpson's rule at 0.05 nm.
double planckIntegralSimpson(double a, double b, double T) {
    const int n = int(std::round((b - a) / 0.05));
    const double h = (b - a) / n;
    double s = planck(a, T) + planck(b, T);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * planck(a + i * h, T);
    return s * h / 3.0 * 1e-9;
}

// A fire-like shader: one grey component on slot "density", emission at slot "temperature".
ShaderDesc emissiveShader(float sigmaA, float sigmaS, float minTemperature) {
    ShaderDesc s = test::greyShader(sigmaA, sigmaS);
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    e.minTemperature = minTemperature;
    s.emission = e;
    return s;
}

std::unique_ptr<Medium> isothermalBlock(int n, double h, float sigmaA, float T, float minT,
                                        const Transform& xf = Transform()) {
    std::vector<FloatGrid> grids;
    grids.push_back(test::makeGrid([](int, int, int) { return 1.f; }, 0, n - 1, h));
    grids.push_back(
        test::makeGrid([T](int, int, int) { return T; }, 0, n - 1, h, Vec3d(0.0), "temperature"));
    return std::make_unique<Medium>(emissiveShader(sigmaA, 0.5f, minT), std::move(grids), xf, 1.f,
                                    8);
}

}  // namespace

TEST(MediumEmitter, IsothermalBlockPowerIsFourPiSigmaAVolumeRadiance) {
    const int n = 16;
    const double h = 0.05;
    for (float T : {1200.f, 2000.f, 3500.f}) {
        auto m = isothermalBlock(n, h, 0.8f, T, 500.f);
        MediumEmitter emitter(*m);
        const double V = std::pow(n * h, 3);
        const double expected =
            4.0 * double(kPi) * 0.8 * V * planckIntegralSimpson(360.0, 830.0, T);
        EXPECT_EQ(emitter.emittingVoxels(), size_t(n * n * n));
        EXPECT_NEAR(emitter.tablePower() / expected, 1.0, 0.005) << "T = " << T;
    }
    // The volume is the world's: a uniform scale of 2 makes 8 times the power.
    auto scaled = isothermalBlock(n, h, 0.8f, 2000.f, 500.f, Transform::scale(Vec3d(2.0)));
    auto plain = isothermalBlock(n, h, 0.8f, 2000.f, 500.f);
    EXPECT_NEAR(MediumEmitter(*scaled).tablePower() / MediumEmitter(*plain).tablePower(), 8.0,
                1e-4);
}

TEST(MediumEmitter, EmittedWavelengthsFollowPlanck) {
    // min_temperature just below T: the blurred fringe of the block hardly emits, so nearly
    // every photon comes from the isothermal interior, where p(λ) ∝ B(λ, T) v(λ) (v: the
    // camera's wavelength density) and w ∝ 1/v(λ). The histogram is of weights (what the
    // photon pass carries), its variance Σ w² per bin.
    const float T = 2000.f;
    auto m = isothermalBlock(8, 0.1, 1.f, T, T - 1.f);
    MediumEmitter emitter(*m);
    Medium::Context ctx(*m);
    constexpr int kBins = 47;  // 10 nm each over 360–830 nm
    std::vector<double> sumW(kBins, 0.0), sumW2(kBins, 0.0);
    double total = 0.0;
    int accepted = 0, unitWeight = 0, visible = 0;
    // In the interior w v(λ) = ∫B v dλ / ∫B dλ, the same for every photon.
    double bv = 0.0, bSum = 0.0;
    for (int l = 360; l <= 830; ++l) {
        bv += planck(l, T) * SampledWavelengths::visiblePdf(float(l));
        bSum += planck(l, T);
    }
    const double wv = bv / bSum;
    for (uint64_t i = 0; i < 200000; ++i) {
        Sampler sampler(7, i, 0);
        PhotonEmission em;
        if (!emitter.sample(sampler, ctx, &em)) continue;
        EXPECT_NEAR(length(em.direction), 1.f, 1e-4f);
        unitWeight +=
            std::abs(em.weight * SampledWavelengths::visiblePdf(em.lambda) / wv - 1.0) < 0.01;
        visible += em.lambda < 700.f;
        int b = std::min(kBins - 1, int((em.lambda - 360.f) / 10.f));
        sumW[size_t(b)] += em.weight;
        sumW2[size_t(b)] += double(em.weight) * em.weight;
        total += em.weight;
        ++accepted;
    }
    ASSERT_GT(accepted, 100000);
    EXPECT_GT(unitWeight, 0.99 * accepted);  // f V / (Φ_cell p) ∝ 1/v in an isothermal block
    // Most photons where the film sees them: at 2000 K, 31 % of the 360–830 nm power lies
    // below 700 nm, and 67 % of the photons drawn ∝ B v.
    EXPECT_NEAR(double(visible) / accepted, 0.668, 0.01);
    const double planckTotal = planckIntegralSimpson(360.0, 830.0, T);
    double chi2 = 0.0;
    for (int b = 0; b < kBins; ++b) {
        double expected =
            total * planckIntegralSimpson(360.0 + 10 * b, 370.0 + 10 * b, T) / planckTotal;
        chi2 += (sumW[size_t(b)] - expected) * (sumW[size_t(b)] - expected) / sumW2[size_t(b)];
    }
    // 46 degrees of freedom: P(χ² > 84) ≈ 5e-4.
    EXPECT_LT(chi2, 84.0);
}

TEST(MediumEmitter, WeightedEstimateMatchesGridIntegralOfUnevenFire) {
    // A hot core (2400 K) cooling to 300 K at the edge, soot densest off-centre: the table
    // (corner means) is not the field, the weights must make up the difference.
    const int n = 12;
    const double h = 0.1;
    auto temperature = [](int i, int j, int k) {
        double r2 = (i - 5.5) * (i - 5.5) + (j - 5.5) * (j - 5.5) + (k - 5.5) * (k - 5.5);
        return float(300.0 + 2100.0 * std::exp(-r2 / 8.0));
    };
    auto density = [](int i, int j, int k) {
        double r2 = (i - 7.0) * (i - 7.0) + (j - 5.0) * (j - 5.0) + (k - 6.0) * (k - 6.0);
        return float(std::exp(-r2 / 10.0));
    };
    std::vector<FloatGrid> grids;
    grids.push_back(test::makeGrid(density, 0, n - 1, h));
    grids.push_back(test::makeGrid(temperature, 0, n - 1, h, Vec3d(0.0), "temperature"));
    Medium m(emissiveShader(2.f, 1.f, 500.f), std::move(grids), Transform(), 1.f, 8);
    MediumEmitter emitter(m);

    // The field's integral: midpoint rule, 6³ points per voxel over the grid's dilated bounds.
    const int sub = 6;
    double integral = 0.0;
    for (int i = -1 * sub; i < (n + 1) * sub; ++i)
        for (int j = -1 * sub; j < (n + 1) * sub; ++j)
            for (int k = -1 * sub; k < (n + 1) * sub; ++k) {
                Vec3 p(float((i + 0.5) / sub * h), float((j + 0.5) / sub * h),
                       float((k + 0.5) / sub * h));
                integral += emitter.powerDensity(p);
            }
    integral *= std::pow(h / sub, 3);

    Medium::Context ctx(m);
    double sum = 0.0, sumSq = 0.0;
    const int N = 200000;
    for (uint64_t i = 0; i < uint64_t(N); ++i) {
        Sampler sampler(11, i, 0);
        PhotonEmission em;
        double w = emitter.sample(sampler, ctx, &em) ? double(em.weight) : 0.0;
        sum += w;
        sumSq += w * w;
    }
    const double mean = sum / N, stderrMean = std::sqrt((sumSq / N - mean * mean) / N);
    const double estimate = emitter.tablePower() * mean;
    // 1.5 %: over seeds 11–14 the estimate sits +0.6 to +1.3 % above the reference, whether λ
    // is drawn ∝ B or ∝ B v (σ 0.2 % and 0.4 %): a bias of the midpoint reference or of the
    // slivers medium_emitter.h leaves out, not of the wavelength sampling.
    EXPECT_NEAR(estimate / integral, 1.0, std::max(0.015, 3.0 * stderrMean / mean))
        << "table " << emitter.tablePower() << " W, mean weight " << mean << " ± " << stderrMean;
    // The table alone overestimates (B grows exponentially with T, so the mean of the corners'
    // emission exceeds the emission of the interpolated temperature): the weights correct it.
    EXPECT_GT(emitter.tablePower(), integral);
}

TEST(MediumEmitter, PhotonPassChoosesLightsAndMediaByPower) {
    // An isothermal block beside a point light of the same order of power: the share of photons
    // from the medium is Φ_m / (Φ_m + Φ_l) (binomial, 4σ), and the photons' summed power is the
    // lights' plus the medium's. The light stands within the block's bounding sphere, where
    // it sends all its power towards the scene (lights.cpp, sceneCone).
    auto m = isothermalBlock(8, 0.1, 1.f, 1500.f, 500.f);
    const double mediumPower = MediumEmitter(*m).tablePower();
    auto light = makePointLight(Vec3(0.9f, 0.4f, 0.4f), float(2.0 * mediumPower), Spectrum(1.f));
    PhotonPassSettings ps;
    ps.photons = 60000;
    ps.seed = 4;
    ps.progress = Progress::Mode::Quiet;
    PhotonPassStats stats;
    ASSERT_EQ(light->emittedPower(m->worldBounds()), float(2.0 * mediumPower));
    tracePhotons({light.get()}, {m.get()}, ps, &stats);
    const double p = mediumPower / (mediumPower + 2.0 * mediumPower);
    const double n = double(ps.photons);
    EXPECT_NEAR(double(stats.fromMedia) / n, p, 4.0 * std::sqrt(p * (1 - p) / n));
    EXPECT_NEAR(stats.mediumPower, mediumPower, 1e-6 * mediumPower);
    // The medium's photons carry weight 1 inside the block and less in its blurred fringe.
    EXPECT_NEAR(stats.emittedPower / (3.0 * mediumPower), 1.0, 0.1);
    EXPECT_LE(stats.emittedPower, 3.0 * mediumPower * 1.001);
}
