// Henyey–Greenstein: normalisation, sampling matches the pdf (χ²) and inverts the CDF exactly
// down to g → 0, mean cosine equals g. The other lobes of a component (Schlick, Rayleigh, Mie
// hazy and murky, double HG, water): normalisation, χ², reported pdf = value, mean cosine, and
// the shader keys that choose them.
#include "medium/phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include "chi_square.h"
#include "core/error.h"
#include "core/rng.h"
#include "scene/shader_loader.h"
#include "scene/toml_reader.h"

using namespace mirage;

class PhaseHG : public ::testing::TestWithParam<float> {};

TEST_P(PhaseHG, NormalisesToOne) {
    HGPhase p(GetParam());
    // ∫ p dω = 2π ∫_{-1}^{1} p(μ) dμ, midpoint rule on a fine grid (the peak at g = 0.95 is
    // ~1e3 wide in μ, so 2e6 cells resolve it).
    const int n = 2000000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += p.eval(-1.f + (i + 0.5f) * 2.f / n);
    EXPECT_NEAR(sum * 2.0 / n * 2.0 * M_PI, 1.0, 2e-4);
}

TEST_P(PhaseHG, SamplesMatchPdfChiSquare) {
    const float g = GetParam();
    HGPhase p(g);
    const int bins = 40, n = 400000;
    std::vector<double> observed(bins, 0.0);
    Vec3 wi = normalize(Vec3(0.3f, -0.5f, 0.8f));
    Sampler s(7, 0, 0);
    for (int i = 0; i < n; ++i) {
        float pdf;
        Vec3 wo = p.sample(wi, s.get1D(), s.get1D(), &pdf);
        ASSERT_NEAR(length(wo), 1.f, 1e-4f);
        ASSERT_NEAR(pdf, p.eval(wi, wo), 1e-3f * pdf);
        float mu = clamp(dot(wi, wo), -1.f, 0.999999f);
        observed[int((mu + 1.f) * 0.5f * bins)] += 1;
    }
    // Expected counts by integrating the pdf over each μ bin (fine midpoint rule).
    double chi2 = 0.0;
    int dof = 0;
    for (int b = 0; b < bins; ++b) {
        double lo = -1.0 + 2.0 * b / bins, hi = lo + 2.0 / bins, e = 0.0;
        const int sub = 2000;
        for (int k = 0; k < sub; ++k)
            e += p.eval(float(lo + (k + 0.5) * (hi - lo) / sub)) * (hi - lo) / sub;
        e *= 2.0 * M_PI * n;
        if (e < 5) continue;  // χ² needs ≥ 5 expected per bin; pool the rest
        chi2 += (observed[b] - e) * (observed[b] - e) / e;
        ++dof;
    }
    // 99.9 % quantile of χ² with ≤ 39 dof is 72.1.
    EXPECT_LT(chi2, 72.1) << "g = " << g << ", dof " << dof - 1;
}

TEST_P(PhaseHG, MeanCosineIsG) {
    const float g = GetParam();
    HGPhase p(g);
    Sampler s(11, 0, 0);
    const int n = 200000;
    double sum = 0.0, sum2 = 0.0;
    Vec3 wi(0, 0, 1);
    for (int i = 0; i < n; ++i) {
        Vec3 wo = p.sample(wi, s.get1D(), s.get1D(), nullptr);
        sum += wo.z;
        sum2 += double(wo.z) * wo.z;
    }
    double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, g, 4.0 * sigma + 1e-4);
}

// The sampled cosines of stratified u, sorted, against the HG CDF in double precision,
//     F(μ) = (1 − g²)/(2g) [1/√(1 + g² − 2gμ) − 1/(1 + g)],   F(μ) = (1 + μ)/2 at g = 0:
// the k-th of n must sit at F = (k + ½)/n, to the rounding of a float cosine. This resolves
// |g| far below what a histogram of random samples can: isotropic samples reported with the
// pdf of g = 1e-4 are off by ~(3g/4)(1 − μ²) in F. The stratified mean cosine must be g.
TEST_P(PhaseHG, SampledCosinesInvertTheCdf) {
    const double g = HGPhase(GetParam()).g();
    auto cdf = [g](double mu) {
        if (g == 0.0) return 0.5 * (1.0 + mu);
        return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) -
                                             1.0 / (1.0 + g));
    };
    const int n = 200000;
    std::vector<double> mu(n);
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        mu[size_t(i)] = HGPhase::sampleCosTheta(float(g), (float(i) + 0.5f) / float(n));
        sum += mu[size_t(i)];
    }
    std::sort(mu.begin(), mu.end());
    double worst = 0.0;
    for (int i = 0; i < n; ++i)
        worst = std::max(worst, std::abs(cdf(mu[size_t(i)]) - (i + 0.5) / n));
    // A float cosine is rounded by ~6e-8 and its formula's own rounding adds a few times that;
    // that moves F by up to 2π p(μ) times as much, largest at the lobe's peak.
    const HGPhase p{float(g)};
    const double tol = 2e-6 + 4e-7 * std::max(p.eval(1.f), p.eval(-1.f)) * 2.0 * M_PI;
    EXPECT_LT(worst, tol) << "g = " << g;
    EXPECT_NEAR(sum / n, g, 2e-6 + 1e-3 * std::abs(g)) << "g = " << g;
}

INSTANTIATE_TEST_SUITE_P(Asymmetries, PhaseHG,
                         ::testing::Values(-0.9f, -0.3f, -5e-4f, 0.f, 1e-4f, 5e-4f, 0.5f, 0.95f));

// ---- The other lobes of a component (ComponentPhase) -------------------------------------

namespace {

struct Lobe {
    const char* name;
    ComponentPhase phase;
};

std::ostream& operator<<(std::ostream& os, const Lobe& l) { return os << l.name; }

// ∫ f(μ) dμ over [−1, 1] by the midpoint rule on n cells.
template <typename F>
double integrateMu(F&& f, int n = 2000000) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += f(-1.0 + (i + 0.5) * 2.0 / n);
    return sum * 2.0 / n;
}

}  // namespace

class PhaseLobe : public ::testing::TestWithParam<Lobe> {};

TEST_P(PhaseLobe, NormalisesToOne) {
    const ComponentPhase& p = GetParam().phase;
    EXPECT_NEAR(2.0 * M_PI * integrateMu([&](double mu) { return p.eval(float(mu)); }), 1.0,
                2e-4);
}

TEST_P(PhaseLobe, SamplesMatchPdfChiSquare) {
    const ComponentPhase& p = GetParam().phase;
    const int bins = 40, n = 400000;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    const Vec3 wi = normalize(Vec3(0.3f, -0.5f, 0.8f));
    Sampler s(13, 0, 0);
    for (int i = 0; i < n; ++i) {
        float pdf;
        const Vec3 wo = p.sample(wi, s.get1D(), s.get1D(), &pdf);
        ASSERT_NEAR(length(wo), 1.f, 1e-4f);
        // The pdf reported is the density of what was sampled: the lobe's value.
        ASSERT_NEAR(pdf, p.eval(dot(wi, wo)), 1e-3f * pdf);
        const float mu = clamp(dot(wi, wo), -1.f, 0.999999f);
        observed[size_t((mu + 1.f) * 0.5f * bins)] += 1;
    }
    for (int b = 0; b < bins; ++b) {
        const double lo = -1.0 + 2.0 * b / bins, hi = lo + 2.0 / bins;
        const int sub = 2000;
        for (int k = 0; k < sub; ++k)
            expected[size_t(b)] += p.eval(float(lo + (k + 0.5) * (hi - lo) / sub)) *
                                   (hi - lo) / sub * 2.0 * M_PI * n;
    }
    const test::ChiSquare c = test::chiSquare(observed, expected);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof)) << GetParam().name;
}

TEST_P(PhaseLobe, MeanCosineMatchesTheLobe) {
    // The sampled mean cosine against ∫ μ p dω of the lobe; printed beside the g it was given.
    const ComponentPhase& p = GetParam().phase;
    const double exact =
        2.0 * M_PI * integrateMu([&](double mu) { return mu * p.eval(float(mu)); });
    Sampler s(17, 0, 0);
    const int n = 400000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double mu = p.sample(Vec3(0, 0, 1), s.get1D(), s.get1D(), nullptr).z;
        sum += mu;
        sum2 += mu * mu;
    }
    const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
    std::printf("%s: mean cosine %.4f (sampled %.4f ± %.4f), g %.3f\n", GetParam().name, exact,
                mean, sigma, p.g());
    EXPECT_NEAR(mean, exact, 4.0 * sigma + 1e-4) << GetParam().name;
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, PhaseLobe,
    ::testing::Values(Lobe{"rayleigh", ComponentPhase(PhaseKind::Rayleigh)},
                      Lobe{"mie_hazy", ComponentPhase(PhaseKind::MieHazy)},
                      Lobe{"mie_murky", ComponentPhase(PhaseKind::MieMurky)},
                      Lobe{"schlick_0", ComponentPhase(PhaseKind::Schlick, 0.f)},
                      Lobe{"schlick_0.5", ComponentPhase(PhaseKind::Schlick, 0.5f)},
                      Lobe{"schlick_-0.7", ComponentPhase(PhaseKind::Schlick, -0.7f)},
                      Lobe{"schlick_0.9", ComponentPhase(PhaseKind::Schlick, 0.9f)},
                      Lobe{"double_hg", ComponentPhase(PhaseKind::DoubleHG, 0.8f, -0.4f, 0.7f)},
                      Lobe{"double_hg_one", ComponentPhase(PhaseKind::DoubleHG, 0.5f, -0.9f, 1.f)},
                      Lobe{"water", ComponentPhase(PhaseKind::Water)}),
    [](const ::testing::TestParamInfo<Lobe>& lobe) {
        std::string n = lobe.param.name;
        for (char& ch : n)
            if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
        return n;
    });

TEST(PhaseLobe, ClosedFormsOfTheMeanCosine) {
    // Rayleigh and the Mie lobes are symmetric or not by construction: Rayleigh's mean cosine
    // is 0; a double HG's is w g1 + (1 − w) g2; Mie hazy's is ∫ μ (1 + 9x⁸) dμ / 4 with
    // x = (1 + μ)/2, = 9·(2·(2/10 − 1/9))/4 (substituting μ = 2x − 1) = 0.4.
    auto mean = [](const ComponentPhase& p) {
        return 2.0 * M_PI * integrateMu([&](double mu) { return mu * p.eval(float(mu)); });
    };
    EXPECT_NEAR(mean(ComponentPhase(PhaseKind::Rayleigh)), 0.0, 1e-6);
    EXPECT_NEAR(mean(ComponentPhase(PhaseKind::DoubleHG, 0.8f, -0.4f, 0.7f)),
                0.7 * 0.8 + 0.3 * -0.4, 1e-4);
    EXPECT_NEAR(mean(ComponentPhase(PhaseKind::MieHazy)), 0.4, 1e-4);
}

TEST(PhaseLobe, MieLobesAreThePublishedOnes) {
    // Nishita et al. 1987's lobes as Jarosz 2008 (thesis, ch. 4) and Gutierrez's thesis
    // (eq. 4.24) publish them, normalised over the sphere: (1/4π)(1/2 + (9/2) x⁸) hazy and
    // (1/4π)(1/2 + (33/2) x³²) murky, x = (1 + cosθ)/2. Their mean cosines by quadrature of the
    // published form: 2/5 and 8/17 = 0.4706 (the unnormalised 1 + 50x³² would give 0.567).
    auto hazy = [](double mu) { return (0.5 + 4.5 * std::pow(0.5 * (1 + mu), 8)) / (4 * M_PI); };
    auto murky = [](double mu) { return (0.5 + 16.5 * std::pow(0.5 * (1 + mu), 32)) / (4 * M_PI); };
    EXPECT_NEAR(2.0 * M_PI * integrateMu(hazy), 1.0, 1e-9);
    EXPECT_NEAR(2.0 * M_PI * integrateMu(murky), 1.0, 1e-9);
    const double meanMurky = 2.0 * M_PI * integrateMu([&](double mu) { return mu * murky(mu); });
    EXPECT_NEAR(meanMurky, 8.0 / 17.0, 1e-6);
    const ComponentPhase mirageHazy(PhaseKind::MieHazy), mirageMurky(PhaseKind::MieMurky);
    for (double mu : {-1.0, -0.5, 0.0, 0.5, 0.8, 0.9, 0.95, 0.99, 1.0}) {
        EXPECT_NEAR(mirageHazy.eval(float(mu)), hazy(mu), 1e-5 * hazy(mu)) << mu;
        EXPECT_NEAR(mirageMurky.eval(float(mu)), murky(mu), 1e-5 * murky(mu)) << mu;
    }
    const double mirageMean =
        2.0 * M_PI * integrateMu([&](double mu) { return mu * mirageMurky.eval(float(mu)); });
    EXPECT_NEAR(mirageMean, meanMurky, 1e-4);
}

TEST(PhaseLobe, ShaderKeysChooseTheLobe) {
    const ShaderDesc s = parseShader(
        parseTomlText("[[component]]\nsigma_s = 1.0\nphase = \"double_hg\"\ng = 0.8\ng2 = -0.3\n"
                      "lobe_weight = 0.9\n[[component]]\nsigma_s = 1.0\nphase = \"schlick\"\n"
                      "g = 0.4\n[[component]]\nsigma_s = 1.0\nphase = \"mie_murky\"\n"
                      "[[component]]\nsigma_s = 1.0\nphase = \"rayleigh\"\n",
                      "lobes.toml"),
        "lobes.toml");
    ASSERT_EQ(s.components.size(), 4u);
    EXPECT_EQ(s.components[0].phase, PhaseKind::DoubleHG);
    EXPECT_FLOAT_EQ(s.components[0].g2, -0.3f);
    EXPECT_FLOAT_EQ(s.components[0].phaseWeight, 0.9f);
    EXPECT_EQ(s.components[1].phase, PhaseKind::Schlick);
    EXPECT_FLOAT_EQ(s.components[1].g, 0.4f);
    EXPECT_EQ(s.components[2].phase, PhaseKind::MieMurky);
    EXPECT_EQ(s.components[3].phase, PhaseKind::Rayleigh);
    // A parameter the lobe does not take, and an unknown lobe, are errors naming the key.
    for (const char* bad : {"[[component]]\nphase = \"rayleigh\"\ng = 0.5\n",
                            "[[component]]\nphase = \"hg\"\ng2 = 0.5\n",
                            "[[component]]\nphase = \"mie\"\n"}) {
        std::string msg;
        try {
            parseShader(parseTomlText(bad, "bad.toml"), "bad.toml");
        } catch (const MirageError& e) {
            msg = e.what();
        }
        EXPECT_NE(msg.find("bad.toml:"), std::string::npos) << bad << " → " << msg;
    }
}
