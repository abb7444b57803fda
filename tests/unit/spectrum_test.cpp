// Tests for spectrum/: the embedded CIE 1931 table against the CIE's 1 nm table, the spectral
// → XYZ estimator, Planck's law against published values, and the RGB → spectrum mappings.

#include "spectrum/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "film/color.h"
#include "spectrum/cie.h"
#include "test_support.h"
#include "chi_square.h"

namespace mirage {
namespace {

struct CmfRow {
    float lambda;
    Vec3 xyz;
};

// The CIE data file: a /* … */ header, then "λ x̄ ȳ z̄" rows (CRLF line ends).
std::vector<CmfRow> readCieTable(const std::string& path) {
    std::ifstream in(path);
    std::vector<CmfRow> rows;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
        std::istringstream s(line);
        CmfRow r;
        if (s >> r.lambda >> r.xyz.x >> r.xyz.y >> r.xyz.z) rows.push_back(r);
    }
    return rows;
}

// --- CIE colour-matching functions -------------------------------------------------------------

TEST(CieTest, InterpolatedTableMatchesCie1nmTable) {
    MIRAGE_REQUIRE_SHARED(path, "spectra/cie_1931_2deg_xyz.txt");
    std::vector<CmfRow> rows = readCieTable(path);
    ASSERT_EQ(rows.size(), 471u);
    Vec3 peak(0.f);
    for (const CmfRow& r : rows) peak = vmax(peak, r.xyz);
    double maxRelError = 0.0;
    float worstLambda = 0.f;
    for (const CmfRow& r : rows) {
        Vec3 e = cieXyz(r.lambda);
        for (int c = 0; c < 3; ++c) {
            double err = std::abs(double(e[c]) - r.xyz[c]) / peak[c];
            if (err > maxRelError) maxRelError = err, worstLambda = r.lambda;
        }
        // Every 5th row is in the table itself: those must be exact.
        if (int(r.lambda) % 5 == 0) {
            EXPECT_EQ(e, r.xyz) << r.lambda << " nm";
        }
    }
    std::cout << "[ measured ] max |interpolated − CIE 1 nm| / peak = " << maxRelError << " at "
              << worstLambda << " nm\n";
    EXPECT_LT(maxRelError, 5e-4);  // Sprague refinement; linear interpolation of 5 nm: 9.1e-3
}

TEST(CieTest, YIntegralMatchesCie) {
    // Σ ȳ at 1 nm over 360–830 nm from the embedded table; the CIE value is 106.856895.
    double sum = 0.0;
    for (int l = 360; l <= 830; ++l) sum += cieXyz(float(l)).y;
    std::cout << "[ measured ] ∫ȳ (embedded, 1 nm) = " << std::setprecision(9) << sum
              << " (relative difference " << sum / 106.856895 - 1.0 << ")\n"
              << std::setprecision(6);
    EXPECT_NEAR(sum, 106.856895, 106.856895 * 1e-3);
}

TEST(CieTest, ZeroOutsideTheVisibleRangeAndForNaN) {
    EXPECT_EQ(cieXyz(359.9f), Vec3(0.f));
    EXPECT_EQ(cieXyz(830.1f), Vec3(0.f));
    EXPECT_EQ(cieXyz(std::nanf("")), Vec3(0.f));
    EXPECT_GT(cieXyz(830.f).y, 0.f);
    EXPECT_NEAR(cieXyz(555.f).y, 1.0f, 1e-3f);  // ȳ peaks at 555 nm
}

// A constant radiance 1 has Y = 1 by the normalisation; the Monte Carlo mean over hero-wavelength
// samples drawn from the visible pdf must agree within 3 standard errors.
TEST(CieTest, MonteCarloConstantSpectrumHasUnitY) {
    constexpr int kN = 200000;
    double sum = 0.0, sumSq = 0.0;
    SampledSpectrum one(1.f);
    for (int i = 0; i < kN; ++i) {
        Sampler sampler(7, uint64_t(i), 0);
        SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
        double y = spectrumToXyz(one, w).y;
        sum += y;
        sumSq += y * y;
    }
    double mean = sum / kN;
    double sigma = std::sqrt(std::max(0.0, sumSq / kN - mean * mean) / kN);
    std::cout << "[ measured ] MC mean Y = " << mean << " ± " << sigma << "\n";
    EXPECT_NEAR(mean, 1.0, 3.0 * sigma);
}

TEST(CieTest, WavelengthOfZeroDensityContributesNothing) {
    SampledWavelengths w = SampledWavelengths::sampleVisible(0.3f);
    Vec3 all = spectrumToXyz(SampledSpectrum(1.f), w);
    w.pdf[2] = 0.f;
    Vec3 some = spectrumToXyz(SampledSpectrum(1.f), w);
    EXPECT_TRUE(isFinite(some));
    EXPECT_LT(some.y, all.y);
}

// --- Planck's law ------------------------------------------------------------------------------

// The camera's wavelength sampler (SampledWavelengths::sampleVisible): its draws follow the
// density it reports, that density is visiblePdf's at the drawn λ, and it integrates to 1 over
// [360, 830] nm. Each of the four stratified wavelengths is binned (10-nm bins).
TEST(SampledWavelengthsTest, DrawsFollowTheirDensityChiSquare) {
    constexpr int kBins = 47;
    constexpr double kLo = 360.0, kWidth = 10.0;
    std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
    Sampler rng(17, 0, 0);
    constexpr int kDraws = 100000;
    double worst = 0.0;
    for (int n = 0; n < kDraws; ++n) {
        const SampledWavelengths w = SampledWavelengths::sampleVisible(rng.get1D());
        for (int i = 0; i < kSpectrumSamples; ++i) {
            ASSERT_GE(w.lambda[i], kLambdaMin);
            ASSERT_LE(w.lambda[i], kLambdaMax);
            const int b = std::min(kBins - 1, int((w.lambda[i] - kLo) / kWidth));
            observed[size_t(b)] += 1.0;
            const double ref = SampledWavelengths::visiblePdf(w.lambda[i]);
            worst = std::max(worst, std::abs(w.pdf[i] - ref) / ref);
        }
    }
    EXPECT_LT(worst, 1e-5) << "the reported density is visiblePdf's at the drawn wavelength";
    double integral = 0.0;
    for (int b = 0; b < kBins; ++b) {
        const double a = kLo + b * kWidth, z = std::min(a + kWidth, double(kLambdaMax));
        constexpr int kSub = 200;
        double mass = 0.0;
        for (int k = 0; k < kSub; ++k)
            mass += SampledWavelengths::visiblePdf(float(a + (k + 0.5) * (z - a) / kSub)) *
                    (z - a) / kSub;
        integral += mass;
        expected[size_t(b)] = mass * kDraws * kSpectrumSamples;
    }
    EXPECT_NEAR(integral, 1.0, 1e-4);
    const test::ChiSquare fit = test::chiSquare(observed, expected);
    EXPECT_LT(fit.statistic, test::chiSquareCritical(fit.dof)) << "dof " << fit.dof;
}

TEST(PlanckTest, MatchesPublishedValues) {
    // Spectral radiance in W·m⁻²·sr⁻¹·m⁻¹ (../shared/data/README.md, "Planck check values").
    struct Check {
        double lambdaNm, temperatureK, radiance;
    };
    const Check checks[] = {{483, 6000, 3.1849e13},
                            {600, 6000, 2.86772e13},
                            {500, 3700, 1.59845e12},
                            {600, 4500, 7.46497e12}};
    for (const Check& c : checks) {
        double b = planck(c.lambdaNm, c.temperatureK);
        EXPECT_NEAR(b / c.radiance, 1.0, 1e-4) << c.lambdaNm << " nm, " << c.temperatureK << " K";
    }
}

TEST(PlanckTest, FiniteAtExtremeTemperatures) {
    for (double t : {1.0, 1e5}) {
        for (double l = 1.0; l <= 1e6; l *= 1.5) {
            double b = planck(l, t);
            EXPECT_TRUE(std::isfinite(b)) << l << " nm, " << t << " K";
            EXPECT_GE(b, 0.0);
        }
    }
    EXPECT_EQ(planck(500.0, 1.0), 0.0);  // e^(−28 778): no visible light from a 1 K body
    EXPECT_GT(planck(500.0, 1e5), 0.0);
    EXPECT_EQ(planck(500.0, 0.0), 0.0);
    EXPECT_EQ(planck(500.0, -300.0), 0.0);
    EXPECT_EQ(planck(500.0, std::nan("")), 0.0);
}

// Wien's displacement law: λ_max T = b = 2.897771955e-3 m·K (CODATA 2018).
TEST(PlanckTest, PeakFollowsWiensLaw) {
    for (double t : {1500.0, 3000.0, 5800.0, 10000.0}) {
        // Golden-section search for the maximum over 50 nm – 10 µm (unimodal there).
        const double g = 0.5 * (std::sqrt(5.0) - 1.0);
        double a = 50.0, b = 10000.0;
        for (int i = 0; i < 200; ++i) {
            double c = b - g * (b - a), d = a + g * (b - a);
            if (planck(c, t) > planck(d, t))
                b = d;
            else
                a = c;
        }
        double peakM = 0.5 * (a + b) * 1e-9;
        EXPECT_NEAR(peakM * t / 2.897771955e-3, 1.0, 1e-6) << t << " K";
    }
}

TEST(SpectrumTest, BlackbodyNormalizedPeaksAtOne) {
    Spectrum s = blackbodyNormalized(6500.f);
    EXPECT_FLOAT_EQ(s.maxValue(), 1.f);
    // 6500 K peaks at 446 nm, inside the range: the spectrum falls towards red.
    EXPECT_GT(s(450.f), s(700.f));
    Spectrum cold = blackbodyNormalized(1.f);
    EXPECT_TRUE(cold.isConstant());
    EXPECT_EQ(cold.constantValue(), 0.f);
    Spectrum hot = blackbodyNormalized(1e5f);
    EXPECT_FLOAT_EQ(hot.maxValue(), 1.f);
    EXPECT_FLOAT_EQ(hot(360.f), 1.f);  // peak far in the ultraviolet
}

// --- Spectrum ----------------------------------------------------------------------------------

TEST(SpectrumTest, TableIsPiecewiseLinearAndHeldBeyondEnds) {
    Spectrum s = Spectrum::fromTable({400.f, 500.f, 600.f}, {1.f, 3.f, 2.f});
    EXPECT_FALSE(s.isConstant());
    EXPECT_FLOAT_EQ(s(450.f), 2.f);
    EXPECT_FLOAT_EQ(s(550.f), 2.5f);
    EXPECT_FLOAT_EQ(s(380.f), 1.f);
    EXPECT_FLOAT_EQ(s(700.f), 2.f);
    EXPECT_FLOAT_EQ(s(200.f), 1.f);  // outside [360, 830]: clamped to the ends
    EXPECT_FLOAT_EQ(s(2000.f), 2.f);
    EXPECT_FLOAT_EQ(s(std::nanf("")), 1.f);
    EXPECT_FLOAT_EQ(s.maxValue(), 3.f);
    EXPECT_FLOAT_EQ(s.scaled(2.f)(500.f), 6.f);

    SampledWavelengths w = SampledWavelengths::sampleVisible(0.1f);
    SampledSpectrum v = s.sample(w);
    for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_EQ(v[i], s(w.lambda[i]));

    EXPECT_FLOAT_EQ(Spectrum::fromTable({550.f}, {0.25f})(400.f), 0.25f);
    EXPECT_THROW(Spectrum::fromTable({500.f, 400.f}, {1.f, 2.f}), MirageError);
    EXPECT_THROW(Spectrum::fromTable({400.f, 500.f}, {1.f}), MirageError);
    EXPECT_THROW(Spectrum::fromTable({}, {}), MirageError);
    EXPECT_THROW(Spectrum::fromTable({400.f, 500.f}, {1.f, std::nanf("")}), MirageError);
}

TEST(SpectrumTest, ConstantSpectrum) {
    Spectrum s(0.5f);
    EXPECT_TRUE(s.isConstant());
    EXPECT_EQ(s(412.f), 0.5f);
    EXPECT_EQ(s.sample(SampledWavelengths::sampleVisible(0.7f)).average(), 0.5f);
    EXPECT_EQ(Spectrum()(500.f), 0.f);
    // Y of a constant 1 is 1 up to the embedded table's ∫ȳ (see CieTest.YIntegralMatchesCie).
    EXPECT_NEAR(spectrumToXyz(Spectrum(1.f)).y, 1.0, 1e-3);
}

TEST(SpectrumTest, ReflectanceOfGreyIsThatConstant) {
    for (float a : {0.f, 0.18f, 0.5f, 1.f, 3.f}) {
        Spectrum s = rgbReflectanceSpectrum(Vec3(a));
        EXPECT_TRUE(s.isConstant());
        for (float l = 360.f; l <= 830.f; l += 0.5f) ASSERT_EQ(s(l), a) << l << " nm";
    }
}

TEST(SpectrumTest, ReflectanceBasisIsAPartitionOfUnityInUnitInterval) {
    Spectrum r = rgbReflectanceSpectrum({1.f, 0.f, 0.f});
    Spectrum g = rgbReflectanceSpectrum({0.f, 1.f, 0.f});
    Spectrum b = rgbReflectanceSpectrum({0.f, 0.f, 1.f});
    for (float l = 360.f; l <= 830.f; l += 1.f) EXPECT_NEAR(r(l) + g(l) + b(l), 1.f, 1e-6f);
    // Each window covers its own part of the spectrum (cross-overs at 490 and 590 nm).
    EXPECT_GT(b(440.f), 0.95f);
    EXPECT_GT(g(540.f), 0.9f);
    EXPECT_GT(r(650.f), 0.95f);
    EXPECT_NEAR(b(490.f), g(490.f), 0.02f);
    EXPECT_NEAR(g(590.f), r(590.f), 0.02f);

    Sampler rng(3, 0, 0);
    for (int i = 0; i < 200; ++i) {
        Vec3 rgb(rng.get1D(), rng.get1D(), rng.get1D());
        Spectrum s = rgbReflectanceSpectrum(rgb);
        for (float l = 360.f; l <= 830.f; l += 1.f) {
            ASSERT_GE(s(l), 0.f);
            ASSERT_LE(s(l), 1.f);
        }
    }
}

TEST(SpectrumTest, IlluminantRoundTripsThroughXyz) {
    ColorPipeline color("", "ACEScg");
    const Mat3& toWorking = color.xyzToWorking();
    const Vec3 colours[] = {{1.f, 1.f, 1.f},    {0.18f, 0.18f, 0.18f}, {1.f, 0.5f, 0.25f},
                            {0.4f, 0.5f, 0.9f}, {0.8f, 0.7f, 0.2f},    {20.f, 12.f, 6.f}};
    double maxError = 0.0;
    for (const Vec3& rgb : colours) {
        Spectrum s = rgbIlluminantSpectrum(rgb, toWorking);
        EXPECT_GE(s.maxValue(), 0.f);
        Vec3d back = toWorking.apply(spectrumToXyz(s));
        for (int c = 0; c < 3; ++c) {
            double err = std::abs(back[c] - rgb[c]) / std::max(1.0, double(rgb[c]));
            maxError = std::max(maxError, err);
            EXPECT_NEAR(back[c], rgb[c], 1e-4 * std::max(1.f, rgb[c]));
        }
    }
    std::cout << "[ measured ] illuminant rgb → spectrum → rgb max error = " << maxError << "\n";
}

TEST(SpectrumTest, SaturatedIlluminantIsClampedNonNegative) {
    ColorPipeline color("", "ACEScg");
    for (const Vec3& rgb : {Vec3(0.f, 0.f, 1.f), Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f)}) {
        Spectrum s = rgbIlluminantSpectrum(rgb, color.xyzToWorking());
        for (float l = 360.f; l <= 830.f; l += 1.f) ASSERT_GE(s(l), 0.f) << l << " nm";
        EXPECT_GT(s.maxValue(), 0.f);
    }
}

}  // namespace
}  // namespace mirage
