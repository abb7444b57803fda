// The extremes matrix, slab limits, through `mirage slab` (the photon walk of the
// photon pass between two faces):
//   thin slab, τ → 0, normal incidence, n = 1, isotropic phase, albedo a: single scattering
//     R₁ = (a/2) ∫₀¹ μ/(1 + μ) (1 − e^{−τ(1 + 1/μ)}) dμ (scatter at depth τ' with e^{−τ'} dτ',
//     escape at cosine μ with e^{−τ'/μ}); multiple scattering adds O(τ ln(1/τ)) relative.
//   thick slab, τ = 1e6: the adding-doubling semi-infinite row of ../shared/data/README.md.
//   albedo 0: transmittance e^{−τ} (Beer–Lambert).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "test_support.h"

using namespace mirage;

namespace {

double slabValue(const std::string& out, const std::string& key) {
    std::string needle = "\"" + key + "\":";
    size_t at = out.find(needle);
    if (at == std::string::npos) {
        ADD_FAILURE() << "no \"" << key << "\" in:\n" << out;
        return NAN;
    }
    return std::strtod(out.c_str() + at + needle.size(), nullptr);
}

}  // namespace

TEST(Extremes, ThinSlabIsSingleScattering) {
    const double a = 0.9, tau = 0.01;
    // R₁ by the midpoint rule in μ (the integrand is smooth; 1e5 steps: error ≪ 1e-6).
    double R1 = 0;
    const int steps = 100000;
    for (int i = 0; i < steps; ++i) {
        double mu = (i + 0.5) / steps;
        R1 += 0.5 * a * mu / (1 + mu) * (1 - std::exp(-tau * (1 + 1 / mu))) / steps;
    }
    std::string out;
    ASSERT_EQ(test::runMirage("slab --json -q --albedo 0.9 --tau 0.01 --g 0 --photons 4000000 "
                              "--seed 21",
                              &out),
              0)
        << out;
    double R = slabValue(out, "reflectance_diffuse"), se = slabValue(out, "reflectance_stderr");
    std::printf("thin slab τ = %g, a = %g: R = %.6f ± %.6f, single scattering R1 = %.6f\n", tau,
                a, R, se, R1);
    // Multiple scattering adds O(τ ln(1/τ)) relative (a·τ·ln(1/τ)/2 ≈ 2 % here): R is at least
    // R1 and at most 4 % above it.
    EXPECT_GT(R, R1 - 3 * se);
    EXPECT_LT(R, R1 * 1.04 + 3 * se);
    EXPECT_NEAR(slabValue(out, "transmittance_unscattered"), std::exp(-tau), 4 * se + 1e-4);
}

TEST(Extremes, ThickSlabMatchesAddingDoubling) {
    // ../shared/data/README.md, slab table: albedo 0.8, τ = ∞, g = 0, n = 1: UR1 = 0.28525.
    MIRAGE_REQUIRE_SHARED(readme, "README.md");
    std::string out;
    ASSERT_EQ(test::runMirage("slab --json -q --albedo 0.8 --tau 1e6 --g 0 --photons 200000 "
                              "--seed 22",
                              &out),
              0)
        << out;
    double R = slabValue(out, "reflectance"), se = slabValue(out, "reflectance_stderr");
    std::printf("thick slab τ = 1e6, a = 0.8: R = %.5f ± %.5f, adding-doubling 0.28525\n", R, se);
    EXPECT_NEAR(R, 0.28525, std::max(3 * se, 0.01 * 0.28525));
    EXPECT_EQ(slabValue(out, "transmittance"), 0.0);
    EXPECT_EQ(slabValue(out, "capped"), 0.0);
}

TEST(Extremes, AbsorbingSlabIsBeerLambert) {
    std::string out;
    ASSERT_EQ(test::runMirage("slab --json -q --albedo 0 --tau 3 --photons 400000 --seed 23",
                              &out),
              0)
        << out;
    double T = slabValue(out, "transmittance"), se = slabValue(out, "transmittance_stderr");
    std::printf("absorbing slab τ = 3: T = %.5f ± %.5f, e^-3 = %.5f\n", T, se, std::exp(-3.0));
    EXPECT_NEAR(T, std::exp(-3.0), 4 * se);
    EXPECT_EQ(slabValue(out, "reflectance"), 0.0);
}

