// The piecewise-constant distributions (core/distribution.h): samples follow the density, on
// weights with runs of empty bins and with a few bins holding almost all (a sun in a sky map's
// row), and a 2D distribution's cells follow its density too.
#include "core/distribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "chi_square.h"

namespace mirage {
namespace {

std::vector<std::vector<double>> weightSets() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<double> runs(1024), sun(1024, 1e-4), empty(7, 0.0), sparse(300);
    for (size_t i = 0; i < runs.size(); ++i) runs[i] = (i / 37) % 3 == 1 ? 0.0 : uniform(rng);
    for (size_t i = 500; i < 508; ++i) sun[i] = 1e3 * (1.0 + uniform(rng));
    for (size_t i = 0; i < sparse.size(); ++i) sparse[i] = i % 50 == 7 ? uniform(rng) : 0.0;
    return {runs, sun, empty, sparse};
}

TEST(Distribution1D, SamplesFollowTheDensity) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uniform(0.f, 1.f);
    for (const auto& weights : weightSets()) {
        const Distribution1D d(weights);
        constexpr int kSamples = 200000;
        std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
        for (int i = 0; i < kSamples; ++i) {
            size_t bin;
            d.sample(uniform(rng), &bin);
            observed[bin] += 1.0;
        }
        for (size_t i = 0; i < weights.size(); ++i)
            expected[i] = kSamples * d.pdf((double(i) + 0.5) / double(weights.size())) /
                          double(weights.size());
        const test::ChiSquare chi = test::chiSquare(observed, expected);
        EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof)) << weights.size() << " bins";
    }
}

// The bin drawn for u is the one whose CDF interval [c_i, c_i+1) holds it, found by a linear
// scan (empty bins, whose intervals are empty, never drawn), at the edges of every interval, at
// the edges of the guide table's n equal parts of [0, 1) (where u·n may round up onto the next
// part) and between them: the guided search finds a binary search's answer.
TEST(Distribution1D, BinIsTheIntervalHoldingU) {
    for (const auto& weights : weightSets()) {
        const Distribution1D d(weights);
        double total = 0.0;
        for (double w : weights) total += w;
        std::vector<double> cdf(1, 0.0);
        for (double w : weights) cdf.push_back(cdf.back() + (total > 0.0 ? w : 1.0));
        for (double& c : cdf) c /= cdf.back();
        std::vector<float> us;
        for (double c : cdf) us.insert(us.end(), {float(c), std::nextafter(float(c), 0.f)});
        for (int k = 0; k < 1000; ++k) us.push_back(float(k) / 1000.f);
        const size_t n = weights.size();
        for (size_t k = 1; k < n; ++k) {
            const float edge = float(double(k) / double(n));
            us.insert(us.end(), {edge, std::nextafter(edge, 0.f), std::nextafter(edge, 1.f)});
        }
        for (float u : us) {
            if (!(u >= 0.f && u < 1.f)) continue;
            size_t expected = 0;
            while (expected + 1 < weights.size() && !(double(u) < cdf[expected + 1])) ++expected;
            size_t bin;
            d.sample(u, &bin);
            EXPECT_EQ(bin, expected) << "u " << u;
        }
    }
}

TEST(Distribution2D, CellsFollowTheDensity) {
    constexpr int kWidth = 16, kHeight = 8, kSamples = 200000;
    std::vector<double> weights(kWidth * kHeight);
    for (size_t i = 0; i < weights.size(); ++i) weights[i] = i % 5 == 0 ? 0.0 : double(i % 7 + 1);
    weights[37] = 400.0;  // a sun
    const Distribution2D d(weights, kWidth, kHeight);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> uniform(0.f, 1.f);
    std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
    for (int i = 0; i < kSamples; ++i) {
        float u, v, pdf;
        size_t drawn;
        d.sample(uniform(rng), uniform(rng), &u, &v, &pdf, &drawn);
        const size_t cell = size_t(v * kHeight) * kWidth + size_t(u * kWidth);
        ASSERT_EQ(drawn, cell);  // the cell the dome takes its radiance from
        ASSERT_FLOAT_EQ(pdf, d.pdf(u, v));
        observed[cell] += 1.0;
    }
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i)
            expected[size_t(j) * kWidth + i] =
                kSamples * d.pdf((i + 0.5f) / kWidth, (j + 0.5f) / kHeight) / (kWidth * kHeight);
    const test::ChiSquare chi = test::chiSquare(observed, expected);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof));
}

}  // namespace
}  // namespace mirage
