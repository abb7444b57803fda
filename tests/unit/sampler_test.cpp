// The sample generators of core/rng.h: the Sobol sampler's known properties (the first two
// Sobol dimensions in natural order, the (0,2)-sequence property of every scrambled pair of
// dimensions, 1-D stratification), each sample being uniform and its pairs independent (what
// unbiasedness needs), the fallback to random numbers past the covered dimensions, and the
// error of a smooth integral with a known answer falling faster than 1/N.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/rng.h"

using namespace mirage;

namespace {

// Points (dimensions 2k, 2k+1) of samples [first, first + n) of one pixel.
std::vector<std::pair<double, double>> pairPoints(uint64_t seed, uint64_t pixel, uint32_t k,
                                                   uint32_t first, uint32_t n) {
    std::vector<std::pair<double, double>> p;
    for (uint32_t i = first; i < first + n; ++i) {
        Sampler s(SamplerKind::Sobol, seed, pixel, i);
        s.setDimension(2 * k);
        const double x = s.get1Dd();
        p.emplace_back(x, s.get1Dd());
    }
    return p;
}

// Whether every elementary interval [a/2^j, (a+1)/2^j) × [b/2^(m−j), (b+1)/2^(m−j)) of area
// 2^-m, for every j, holds exactly one of the 2^m points: a (0,m,2)-net in base 2.
bool isZeroMTwoNet(const std::vector<std::pair<double, double>>& p, int m) {
    for (int j = 0; j <= m; ++j) {
        const int nx = 1 << j, ny = 1 << (m - j);
        std::vector<int> count(size_t(nx * ny), 0);
        for (const auto& [x, y] : p) ++count[size_t(int(x * nx) * ny + int(y * ny))];
        for (int c : count)
            if (c != 1) return false;
    }
    return true;
}

}  // namespace

TEST(Sampler, SobolDimensionsInNaturalOrder) {
    // Van der Corput, and the Pascal-matrix dimension: m_k = 1, 3, 5, 15 (x + 1).
    const double vdc[8] = {0, .5, .25, .75, .125, .625, .375, .875};
    const double d1[8] = {0, .5, .75, .25, .625, .125, .375, .875};
    for (uint32_t i = 0; i < 8; ++i) {
        EXPECT_EQ(sobol::reverseBits(i) * 0x1p-32, vdc[i]) << i;
        EXPECT_EQ(sobol::dimension1(i) * 0x1p-32, d1[i]) << i;
    }
    // Direction numbers m_k << (32 − k): 1, 3, 5, 15 in the leading bits.
    EXPECT_EQ(sobol::dimension1(1), 0x80000000u);
    EXPECT_EQ(sobol::dimension1(2), 0xc0000000u);
    EXPECT_EQ(sobol::dimension1(4), 0xa0000000u);
    EXPECT_EQ(sobol::dimension1(8), 0xf0000000u);
}

TEST(Sampler, EveryScrambledPairIsAZeroTwoSequence) {
    // Owen scrambling and the shuffle of the sample index keep the (0,2)-sequence property:
    // the first 2^m samples, and every aligned block of 2^m after them, are (0,m,2)-nets.
    for (uint64_t pixel : {0ull, 17ull, 123456789ull})
        for (uint32_t k : {0u, 1u, 7u, Sampler::kSobolDimensions / 2 - 1})
            for (int m = 0; m <= 8; ++m) {
                const uint32_t n = 1u << m;
                EXPECT_TRUE(isZeroMTwoNet(pairPoints(3, pixel, k, 0, n), m))
                    << "pixel " << pixel << " pair " << k << " m " << m;
                EXPECT_TRUE(isZeroMTwoNet(pairPoints(3, pixel, k, 5 * n, n), m))
                    << "pixel " << pixel << " pair " << k << " block 5, m " << m;
            }
}

TEST(Sampler, ScramblingDiffersBetweenPixelsSeedsAndPairs) {
    // Stratified, yet not the same points: each (seed, pixel, pair) has its own scramble.
    const auto a = pairPoints(1, 0, 0, 0, 16);
    EXPECT_NE(a, pairPoints(1, 1, 0, 0, 16));
    EXPECT_NE(a, pairPoints(2, 0, 0, 0, 16));
    EXPECT_NE(a, pairPoints(1, 0, 1, 0, 16));
}

TEST(Sampler, EachSampleIsUniformWithIndependentPairs) {
    // Over many pixels (independent scrambles), sample 5's dimensions 0 … 7 are uniform
    // (χ² over 16 bins) and dimensions of different pairs are uncorrelated; this is what makes
    // any estimator that draws its numbers from one sample unbiased.
    const int pixels = 32768, bins = 16;
    const int dims = 8;
    std::vector<std::vector<int>> hist(dims, std::vector<int>(bins, 0));
    double sumProd02 = 0, sumProd13 = 0;
    for (int p = 0; p < pixels; ++p) {
        Sampler s(SamplerKind::Sobol, 9, uint64_t(p), 5);
        double u[dims];
        for (int d = 0; d < dims; ++d) {
            u[d] = s.get1Dd();
            ++hist[d][int(u[d] * bins)];
        }
        sumProd02 += (u[0] - 0.5) * (u[2] - 0.5);
        sumProd13 += (u[1] - 0.5) * (u[3] - 0.5);
    }
    const double expected = double(pixels) / bins;
    for (int d = 0; d < dims; ++d) {
        double chi2 = 0;
        for (int c : hist[d]) chi2 += (c - expected) * (c - expected) / expected;
        EXPECT_LT(chi2, 37.7) << "dimension " << d;  // χ²(15) at p = 0.001
    }
    // Var of (u − ½)(v − ½) for independent uniforms is 1/144: 4σ of the mean.
    const double bound = 4.0 * std::sqrt(1.0 / 144.0 / pixels);
    EXPECT_LT(std::abs(sumProd02 / pixels), bound);
    EXPECT_LT(std::abs(sumProd13 / pixels), bound);
}

TEST(Sampler, RandomKindIsTheCounterBasedStreamAndSobolFallsBackToIt) {
    Sampler legacy(4, 77, 3), random(SamplerKind::Random, 4, 77, 3);
    Sampler sobolS(SamplerKind::Sobol, 4, 77, 3);
    for (uint32_t d = 0; d < Sampler::kSobolDimensions + 16; ++d) {
        const float a = legacy.get1D(), b = random.get1D(), c = sobolS.get1D();
        EXPECT_EQ(a, b) << d;
        if (d >= Sampler::kSobolDimensions) {
            EXPECT_EQ(a, c) << d;
        }
    }
    // Pure functions of (seed, pixel, sample, dimension): the order of construction and of
    // other samplers' draws does not matter.
    Sampler x(SamplerKind::Sobol, 4, 77, 3);
    x.setDimension(5);
    Sampler y(SamplerKind::Sobol, 4, 77, 3);
    for (int d = 0; d < 5; ++d) y.get1D();
    EXPECT_EQ(x.get1D(), y.get1D());
}

TEST(Sampler, Get2DTakesOnePairOfDimensions) {
    Sampler s(SamplerKind::Sobol, 1, 2, 3);
    s.get1D();  // dimension 0: the next pair starts at 2
    float u1, u2;
    s.get2D(&u1, &u2);
    EXPECT_EQ(s.dimension(), 4u);
    Sampler t(SamplerKind::Sobol, 1, 2, 3);
    t.setDimension(2);
    EXPECT_EQ(u1, t.get1D());
    EXPECT_EQ(u2, t.get1D());
    // The random sampler has no pairs and skips nothing.
    Sampler r(SamplerKind::Random, 1, 2, 3);
    r.get1D();
    r.get2D(&u1, &u2);
    EXPECT_EQ(r.dimension(), 3u);
}

namespace {

// Mean squared error over independent pixels of the estimate of ∫ f over [0,1)^dims from n
// samples, dimensions from `first` on.
template <typename F>
double meanSquaredError(SamplerKind kind, uint32_t n, uint32_t first, int dims, double exact,
                        F&& f) {
    const int replicates = 256;
    double sum = 0;
    for (int r = 0; r < replicates; ++r) {
        double estimate = 0;
        for (uint32_t i = 0; i < n; ++i) {
            Sampler s(kind, 11, uint64_t(r), i);
            s.setDimension(first);
            double x[4];
            for (int d = 0; d < dims; ++d) x[d] = s.get1Dd();
            estimate += f(x);
        }
        const double e = estimate / n - exact;
        sum += e * e;
    }
    return sum / replicates;
}

}  // namespace

TEST(Sampler, SmoothIntegralErrorFallsFasterThanOneOverN) {
    // ∫∫ exp(x y) dx dy over the unit square = Σ_k≥1 1/(k · k!). Monte Carlo's mean squared
    // error falls as 1/N; a scrambled (0,2)-sequence's as N^-3 for a smooth integrand (Owen
    // 1997). From N = 16 to 256 the random sampler's MSE must fall by about 16, Sobol's by far
    // more, in the first pair of dimensions and in a padded one alike.
    double exact = 0, term = 1;
    for (int k = 1; k < 20; ++k) {
        term /= k;
        exact += term / k;
    }
    auto f = [](const double* x) { return std::exp(x[0] * x[1]); };
    for (uint32_t first : {0u, 6u}) {
        const double sobolFall = meanSquaredError(SamplerKind::Sobol, 16, first, 2, exact, f) /
                                 meanSquaredError(SamplerKind::Sobol, 256, first, 2, exact, f);
        const double randomFall =
            meanSquaredError(SamplerKind::Random, 16, first, 2, exact, f) /
            meanSquaredError(SamplerKind::Random, 256, first, 2, exact, f);
        EXPECT_GT(sobolFall, 16.0 * 16.0) << "dimensions from " << first;
        EXPECT_GT(randomFall, 16.0 / 2.0) << "dimensions from " << first;
        EXPECT_LT(randomFall, 16.0 * 2.0) << "dimensions from " << first;
    }
}

TEST(Sampler, PaddedPairsBeatRandomNumbersInFourDimensions) {
    // ∫ exp(x0 + x1) cos(x2) (1 + x3)² over [0,1)^4 = (e − 1)² sin 1 · 7/3. Across pairs the
    // samples are matched by independent shuffles, so the interaction of the pairs converges
    // as Monte Carlo does (1/N) while each pair's own part is stratified: a smaller error at
    // every N, never a larger one.
    const double exact = (M_E - 1) * (M_E - 1) * std::sin(1.0) * 7.0 / 3.0;
    auto f = [](const double* x) {
        return std::exp(x[0] + x[1]) * std::cos(x[2]) * (1 + x[3]) * (1 + x[3]);
    };
    for (uint32_t n : {16u, 256u})
        EXPECT_LT(meanSquaredError(SamplerKind::Sobol, n, 0, 4, exact, f),
                  meanSquaredError(SamplerKind::Random, n, 0, 4, exact, f) / 4.0)
            << n << " samples";
}
