// Fluorescence: the emission band η is sampled by its inverse CDF (χ² against the Gaussian
// renormalised over the allowed range), the Stokes rule holds (λo ≥ λi unless anti-Stokes is
// allowed), and the Γ roulette re-emits with probability Σ_c σa,c Γ_c / σa (binomial, 3σ).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "chi_square.h"
#include "core/rng.h"
#include "medium/fluorescence.h"
#include "transport/reemission.h"

using namespace mirage;

namespace {

// χ² of n samples of η(λi → ·) in 1 nm bins over [lo, hi) against the renormalised Gaussian.
test::ChiSquare bandChiSquare(const FluorescenceEmission& e, float lambdaIn, float lo, float hi,
                              int n, float* minOut) {
    Spectrum band = gaussianBand(685.f, 25.f);
    const int bins = int(hi - lo);
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    Sampler s(23, uint64_t(lambdaIn), 0);
    *minOut = 1e9f;
    for (int i = 0; i < n; ++i) {
        float l;
        EXPECT_TRUE(e.sample(lambdaIn, s.get1D(), &l));
        *minOut = std::min(*minOut, l);
        int b = int(std::floor(l - lo));
        if (b >= 0 && b < bins) observed[b] += 1;
    }
    // Expected: ∫ η over each bin (η is linear between whole nm), over ∫ η on the allowed range.
    double allowed = 0.0;
    for (float l = kLambdaMin; l < kLambdaMax; l += 1.f) {
        float a = std::max(l, e.antiStokes() ? kLambdaMin : lambdaIn);
        if (a >= l + 1.f) continue;
        double mass = 0.5 * (band(a) + band(l + 1.f)) * (l + 1.f - a);
        allowed += mass;
        int b = int(std::floor(l - lo));
        if (b >= 0 && b < bins) expected[b] += mass;
    }
    for (double& x : expected) x *= n / allowed;
    return test::chiSquare(observed, expected);
}

}  // namespace

TEST(Fluorescence, GaussianBandHasTheGivenPeakAndWidth) {
    Spectrum b = gaussianBand(685.f, 25.f);
    EXPECT_FLOAT_EQ(b(685.f), 1.f);
    EXPECT_NEAR(b(685.f - 12.5f), 0.5f, 1e-3f);  // half maximum at ± FWHM/2
    EXPECT_NEAR(b(685.f + 12.5f), 0.5f, 1e-3f);
}

TEST(Fluorescence, EmittedWavelengthsFollowEtaChiSquare) {
    FluorescenceEmission e(685.f, 25.f, false);
    float minOut;
    // Absorbed in the blue: the whole band is allowed.
    auto chi = bandChiSquare(e, 450.f, 600.f, 780.f, 200000, &minOut);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof)) << "dof " << chi.dof;
    // Absorbed at 680 nm, inside the band: only its red part may be emitted (Stokes).
    chi = bandChiSquare(e, 680.5f, 600.f, 780.f, 200000, &minOut);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof)) << "dof " << chi.dof;
    EXPECT_GE(minOut, 680.5f);
}

TEST(Fluorescence, EnergyIsNeverCreatedUnlessAntiStokes) {
    FluorescenceEmission stokes(685.f, 25.f, false), anti(685.f, 25.f, true);
    Sampler s(29, 0, 0);
    int below = 0;
    for (int i = 0; i < 100000; ++i) {
        float li = 400.f + 400.f * s.get1D(), lo;
        if (stokes.sample(li, s.get1D(), &lo)) {
            ASSERT_GE(lo, li);
        }
        if (anti.sample(li, s.get1D(), &lo)) below += lo < li;
    }
    EXPECT_GT(below, 1000);  // anti-Stokes emission does happen when allowed
    float minOut;
    auto chi = bandChiSquare(anti, 700.f, 600.f, 780.f, 200000, &minOut);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof)) << "dof " << chi.dof;
    // Past the red end of the band nothing can be emitted.
    float lo;
    EXPECT_FALSE(stokes.sample(829.f, 0.5f, &lo));
    EXPECT_NEAR(stokes.pdf(450.f, 685.f), 1.0 / (25.0 / (2 * std::sqrt(2 * std::log(2.0))) *
                                                 std::sqrt(2 * M_PI)),
                1e-4);
}

TEST(Fluorescence, GammaRouletteReemitsWithTheMeanQuantumYield) {
    // Two constant absorbers: a fluorescent one (Γ = 0.1, σa = 3/m) and a plain one (1/m):
    // P(re-emission) = 0.1 × 3/4 = 0.075.
    ShaderDesc s;
    s.name = "two-absorbers";
    MediumComponent f, plain;
    f.sigmaA = Spectrum(3.f);
    f.quantumEfficiency = 0.1f;
    plain.sigmaA = Spectrum(1.f);
    s.components = {f, plain};
    Bounds3 box;
    box.expand(Vec3(0.f));
    box.expand(Vec3(1.f));
    Medium m(s, box, Transform(), 1.f);
    Medium::Context ctx(m);
    Sampler sampler(31, 0, 0);
    const int n = 400000;
    int reemitted = 0;
    for (int i = 0; i < n; ++i) {
        Reemission r;
        if (!sampleReemission(m, ctx, Vec3(0.5f), 500.f, sampler, &r)) continue;
        ++reemitted;
        ASSERT_EQ(r.component, 0);
        ASSERT_GE(r.lambdaNm, 500.f);
        ASSERT_NEAR(r.powerScale, 500.f / r.lambdaNm, 1e-6f);
        ASSERT_NEAR(length(r.wo), 1.f, 1e-5f);
    }
    const double p = 0.075, sigma = std::sqrt(p * (1 - p) / n);
    EXPECT_NEAR(double(reemitted) / n, p, 3 * sigma);
    std::printf("re-emitted / absorbed = %.5f (expected %.3f ± %.5f)\n", double(reemitted) / n, p,
                sigma);

    // Without a fluorescent component no random number is drawn.
    s.components[0].quantumEfficiency = 0.f;
    Medium plainMedium(s, box, Transform(), 1.f);
    Medium::Context plainCtx(plainMedium);
    Sampler a(37, 0, 0), b(37, 0, 0);
    Reemission r;
    EXPECT_FALSE(sampleReemission(plainMedium, plainCtx, Vec3(0.5f), 500.f, a, &r));
    EXPECT_EQ(a.get1D(), b.get1D());
}

TEST(Fluorescence, PhotonWalkAndAdjointConvertEnergyAlike) {
    // Γ η counts photons; both transports carry energy, so a re-emission from λi to λo keeps
    // the fraction λi/λo of the absorbed energy (Mobley 1994, §5.13). Photon walk: the power
    // scale of a re-emission at λi = 450 nm has mean E_η[λi/λo]. Volpath's adjoint sample
    // (sampleInelasticEvent) must give the same conversion: lit by L(λi) = 1 on
    // [440, 460] nm, the re-emitted energy ∫ dλo Σ Γ ∫ σa η(λi → λo) (λi/λo) L(λi) dλi, over
    // the absorbed energy σa ∫ L dλi, is Γ E[λi/λo] < Γ: no energy is created.
    constexpr float kG = 0.5f, kSigmaA = 2.f;
    ShaderDesc s;
    s.name = "fluorescent";
    MediumComponent f;
    f.sigmaA = Spectrum(kSigmaA);
    f.quantumEfficiency = kG;
    s.components = {f};
    Bounds3 box;
    box.expand(Vec3(0.f));
    box.expand(Vec3(1.f));
    Medium m(s, box, Transform(), 1.f);
    Medium::Context ctx(m);

    // E_η[1/λo] by quadrature of the band (its whole mass lies above 460 nm, so the Stokes
    // renormalisation is 1 for every λi in [440, 460]).
    Spectrum band = gaussianBand(685.f, 25.f);
    double mass = 0, inv = 0;
    for (double l = kLambdaMin; l < kLambdaMax; l += 0.05) {
        mass += band(float(l));
        inv += band(float(l)) / l;
    }
    const double meanInvOut = inv / mass;
    const double walkExpected = 450.0 * meanInvOut;  // E[λi/λo] at λi = 450 nm
    const double adjointExpected = kG * 450.0 * meanInvOut;  // mean λi over [440, 460] is 450

    Sampler sampler(43, 0, 0);
    const int n = 400000;
    double sum = 0, sum2 = 0;
    int reemitted = 0;
    for (int i = 0; i < n; ++i) {
        Reemission r;
        if (!sampleReemission(m, ctx, Vec3(0.5f), 450.f, sampler, &r)) continue;
        ++reemitted;
        sum += r.powerScale;
        sum2 += double(r.powerScale) * r.powerScale;
    }
    double walkMean = sum / reemitted;
    double walkSe = std::sqrt(std::max(0.0, sum2 / reemitted - walkMean * walkMean) / reemitted);
    EXPECT_NEAR(walkMean, walkExpected, 3 * walkSe + 1e-5);

    // The camera path's inelastic event at a collision of majorant σ̄ = 4/m (P_f = Γσa/σ̄ =
    // 1/4): its weight is already divided by σ̄ P_f, so σ̄ × weight estimates the source.
    const double range = kLambdaMax - kLambdaMin;
    const float sigmaMaj = 4.f;
    sum = sum2 = 0;
    int chosen = 0;
    for (int i = 0; i < n; ++i) {
        float lambdaOut = kLambdaMin + float(range) * sampler.get1D();
        SampledWavelengths w;
        w.lambda.fill(lambdaOut);
        w.pdf.fill(1.f);
        const InelasticEvent a =
            sampleInelasticEvent(m, ctx, Vec3(0.5f), w, sigmaMaj, kSigmaA / sigmaMaj, sampler);
        double x = 0;
        chosen += a.chosen;
        if (!a.chosen) {
            EXPECT_FLOAT_EQ(a.otherScale, 1.f / (1.f - kG * kSigmaA / sigmaMaj));
        }
        if (a.chosen && a.lambdaInNm >= 440.f && a.lambdaInNm <= 460.f)
            x = a.weight * sigmaMaj * range / (kSigmaA * 20.0);  // ∫ dλo, over σa ∫ L
        sum += x;
        sum2 += x * x;
    }
    EXPECT_NEAR(double(chosen) / n, kG * kSigmaA / sigmaMaj, 0.005);
    double adjointMean = sum / n;
    double adjointSe = std::sqrt(std::max(0.0, sum2 / n - adjointMean * adjointMean) / n);
    EXPECT_NEAR(adjointMean, adjointExpected, 3 * adjointSe);
    EXPECT_LT(adjointMean + 3 * adjointSe, kG);  // energy out < Γ × energy absorbed
    std::printf("energy re-emitted / absorbed at 450 nm: walk %.4f ± %.4f, adjoint %.4f ± %.4f "
                "(Γ E[λi/λo] = %.4f, Γ = %.2f)\n",
                kG * walkMean, kG * walkSe, adjointMean, adjointSe, adjointExpected, kG);
}
