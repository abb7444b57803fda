// Wavelength sampling by inverse CDF: samples follow S(λ)/∫S (χ² against a blackbody), the
// pdf it reports is that density, zero-valued ranges are never sampled.
#include "spectrum/spectrum_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "core/error.h"
#include "core/rng.h"

using namespace mirage;

namespace {

// Histogram of n samples in 10 nm bins over [360, 830] nm against n ∫_bin S / ∫ S. S is
// linear between whole nanometres, so trapezoids at 1 nm give the exact bin integrals.
test::ChiSquare binnedChiSquare(const Spectrum& s, int n, uint64_t seed) {
    SpectrumSampler sampler(s);
    const int bins = 47;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    Sampler rng(seed, 0, 0);
    for (int i = 0; i < n; ++i) {
        float lambda = sampler.sample(rng.get1D());
        int b = std::min(bins - 1, int((lambda - kLambdaMin) / 10.f));
        observed[b] += 1;
    }
    for (int b = 0; b < bins; ++b) {
        double area = 0;
        for (int k = 0; k < 10; ++k) {
            float l0 = kLambdaMin + float(10 * b + k);
            area += 0.5 * (double(s(l0)) + double(s(l0 + 1.f)));
        }
        expected[b] = n * area / sampler.integral();
    }
    return test::chiSquare(observed, expected);
}

}  // namespace

TEST(SpectrumSampling, BlackbodySamplesPassChiSquare) {
    for (float T : {2700.f, 6500.f}) {
        // Planck's law at 1 nm, in absolute units (the sampler normalises).
        std::vector<float> dense(Spectrum::kDenseSamples);
        for (int i = 0; i < Spectrum::kDenseSamples; ++i)
            dense[i] = float(planck(kLambdaMin + i, T) * 1e-12);
        Spectrum bb = Spectrum::fromDense(dense);
        test::ChiSquare c = binnedChiSquare(bb, 500000, 3);
        EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof)) << T << " K, dof " << c.dof;
    }
}

TEST(SpectrumSampling, PdfIsTheNormalisedSpectrum) {
    Spectrum bb = blackbodyNormalized(4000.f);
    SpectrumSampler sampler(bb);
    // ∫ pdf = 1 (trapezoids, exact for the piecewise-linear density).
    double sum = 0;
    for (int i = 0; i + 1 < Spectrum::kDenseSamples; ++i)
        sum += 0.5 * (sampler.pdf(kLambdaMin + i) + sampler.pdf(kLambdaMin + i + 1));
    EXPECT_NEAR(sum, 1.0, 1e-5);
    Sampler rng(5, 0, 0);
    for (int i = 0; i < 1000; ++i) {
        float pdf;
        float lambda = sampler.sample(rng.get1D(), &pdf);
        ASSERT_GE(lambda, kLambdaMin);
        ASSERT_LE(lambda, kLambdaMax);
        ASSERT_NEAR(pdf, bb(lambda) / sampler.integral(), 1e-5 * pdf);
        ASSERT_NEAR(pdf, sampler.pdf(lambda), 1e-5 * pdf);
    }
    // The one-off form agrees with the sampler.
    float pdfA, pdfB;
    EXPECT_FLOAT_EQ(sampleWavelength(bb, 0.37f, &pdfA), sampler.sample(0.37f, &pdfB));
    EXPECT_FLOAT_EQ(pdfA, pdfB);
}

TEST(SpectrumSampling, ConstantSpectrumIsUniform) {
    SpectrumSampler sampler(Spectrum(2.5f));
    EXPECT_NEAR(sampler.integral(), 2.5 * (kLambdaMax - kLambdaMin), 1e-3);
    EXPECT_NEAR(sampler.sample(0.f), kLambdaMin, 1e-4);
    EXPECT_NEAR(sampler.sample(0.5f), 0.5f * (kLambdaMin + kLambdaMax), 1e-3);
    EXPECT_NEAR(sampler.pdf(500.f), 1.f / (kLambdaMax - kLambdaMin), 1e-7);
    test::ChiSquare c = binnedChiSquare(Spectrum(1.f), 200000, 9);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
}

TEST(SpectrumSampling, NeverSamplesWhereTheSpectrumIsZero) {
    // A box from 500 to 600 nm with 1 nm linear edges; zero elsewhere.
    Spectrum box = Spectrum::fromTable({499.f, 500.f, 600.f, 601.f}, {0.f, 1.f, 1.f, 0.f});
    SpectrumSampler sampler(box);
    Sampler rng(7, 0, 0);
    for (int i = 0; i < 100000; ++i) {
        float lambda = sampler.sample(rng.get1D());
        ASSERT_GE(lambda, 499.f);
        ASSERT_LE(lambda, 601.f);
    }
    for (float u : {0.f, 1e-7f, 0.99999994f, 1.f}) {
        float lambda = sampler.sample(u);
        EXPECT_GE(lambda, 499.f) << u;
        EXPECT_LE(lambda, 601.f) << u;
    }
    EXPECT_EQ(sampler.pdf(450.f), 0.f);
    EXPECT_THROW(SpectrumSampler(Spectrum(0.f)), MirageError);
}
