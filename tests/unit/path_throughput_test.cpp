// The throughput's Russian roulette (transport/path_vertex.h): E[β] kept, and measured against
// the weight a path started with (rouletteScale), so that a second path from a thin edge's lit
// point, whose weight is the edge's coverage, is not cut to a coin at its first vertex.
#include "transport/path_vertex.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace mirage;

namespace {

// The roulette of β = `beta` against `scale`, n times: the share of paths that survive and the
// mean of β afterwards (0 for the ended ones).
void roulette(float beta, float scale, int n, double* survived, double* meanBeta) {
    Sampler sampler(7, 0, 0);
    int alive = 0;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        PathThroughput path;
        path.beta = SampledSpectrum(beta);
        path.rouletteScale = scale;
        if (!path.roulette(sampler)) continue;
        ++alive;
        sum += path.beta[0];
    }
    *survived = double(alive) / n;
    *meanBeta = sum / n;
}

}  // namespace

TEST(PathThroughput, RouletteKeepsTheMeanAgainstAnyScale) {
    const int n = 200000;
    for (float scale : {1.f, 0.2f, 0.02f}) {
        double survived, mean;
        roulette(0.01f, scale, n, &survived, &mean);
        // Survival min(1, β / (scale · threshold)): 0.04, 0.2, 1.
        const double q = std::min(1.0, 0.01 / (scale * kRouletteThreshold));
        EXPECT_NEAR(survived, q, 5 * std::sqrt(q * (1 - q) / n) + 1e-12) << scale;
        EXPECT_NEAR(mean, 0.01, 5 * 0.01 * std::sqrt((1 - q) / (q * n)) + 1e-9) << scale;
    }
}

TEST(PathThroughput, APathAtItsStartingWeightIsNotRouletted) {
    // β equal to the weight the path started with: nothing drawn, β unchanged.
    Sampler sampler(3, 0, 0);
    PathThroughput path;
    path.beta = SampledSpectrum(0.02f);
    path.rouletteScale = 0.02f;
    const uint32_t before = sampler.dimension();
    EXPECT_TRUE(path.roulette(sampler));
    EXPECT_EQ(sampler.dimension(), before);
    EXPECT_EQ(path.beta[0], 0.02f);
}
