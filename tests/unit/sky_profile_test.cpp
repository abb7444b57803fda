// The camera ray's march for the dome's points (render/sky_profile.h): the points, pooled over
// their strata, fall with the profile's density σ̂(t) / depth (χ²) and report the strata's
// density at each; a march over a grid medium reads its optical depth.
#include "render/sky_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "test_support.h"
#include "transport/tracking.h"

using namespace mirage;

TEST(SkyProfile, StratifiedPointsFollowTheProfile) {
    SkyProfile p;
    p.start = 1.f;
    p.step = 0.1f;
    for (int k = 0; k < SkyProfile::kSteps; ++k) {
        // Steps of no medium among steps from thin to dense, as a cloud's edge.
        p.sigma[size_t(k)] = k % 5 == 2 ? 0.f : 0.05f + 0.3f * float((k * 7) % 11);
        p.depth += p.sigma[size_t(k)] * p.step;
    }
    constexpr int kStrata = 4, kHalves = 2;
    const int n = 60000;
    std::vector<double> observed(SkyProfile::kSteps * kHalves, 0.0), expected(observed.size());
    Sampler rng(5, 0, 0);
    int placed = 0;
    for (int i = 0; i < n; ++i) {
        float t[kStrata], pdf[kStrata];
        const int count = p.stratify(rng.get1D(), kStrata, t, pdf);
        ASSERT_GE(count, kStrata - 1);
        for (int j = 0; j < count; ++j) {
            const float x = (t[j] - p.start) / p.step;
            ASSERT_GE(x, 0.f);
            ASSERT_LT(x, float(SkyProfile::kSteps));
            const size_t k = size_t(x);
            // Never in a step of no medium; the density the strata's own.
            ASSERT_GT(p.sigma[k], 0.f) << t[j];
            EXPECT_FLOAT_EQ(pdf[j], kStrata * p.sigma[k] / p.depth);
            if (j > 0) {
                ASSERT_GT(t[j], t[j - 1]);
            }
            observed[size_t(std::min(int(x * kHalves), int(observed.size()) - 1))] += 1;
            ++placed;
        }
    }
    // Each half step holds σ̂ · step / 2 / depth of the pooled points.
    for (size_t b = 0; b < expected.size(); ++b)
        expected[b] = placed * p.sigma[b / kHalves] * p.step / kHalves / p.depth;
    std::vector<double> o, e;  // the bins that can hold points
    for (size_t b = 0; b < expected.size(); ++b) {
        if (expected[b] > 0) {
            o.push_back(observed[b]);
            e.push_back(expected[b]);
        } else {
            EXPECT_EQ(observed[b], 0.0);
        }
    }
    const test::ChiSquare r = test::chiSquare(o, e);
    EXPECT_LT(r.statistic, test::chiSquareCritical(r.dof));
    // A ray of no medium draws nothing.
    SkyProfile empty;
    empty.step = 1.f;
    float t[kStrata], pdf[kStrata];
    EXPECT_EQ(empty.stratify(0.5f, kStrata, t, pdf), 0);
}

TEST(SkyProfile, TheMarchReadsTheOpticalDepth) {
    // A slab of density 1 between x = 8 h and 24 h of a grid over [0, 1]³: σt 3/m; the ray
    // along x at y = z = 0.5 crosses it over 0.5 m (the trilinear fade at its faces is
    // symmetric, so the midpoint sum over 32 steps of the box holds 1.5 within a step's worth).
    const double h = 1.0 / 32;
    auto slab = test::gridMedium([](int i, int, int) { return i >= 8 && i < 24 ? 1.f : 0.f; },
                                 0, 31, h, 1.f, 2.f);
    TrackingContext tracking({slab.get()});
    const Ray r{Vec3(-0.5f, 0.5f, 0.5f), Vec3(1, 0, 0), kInfinity};
    float a, b;
    ASSERT_TRUE(slab->objectBounds().intersect(r.o, r.d, 0.f, kInfinity, &a, &b));
    const SkyProfile p = SkyProfile::march(*slab, tracking.context(0), r, a, b);
    EXPECT_NEAR(p.depth, 3.0 * 0.5, 3.0 * p.step);
    EXPECT_NEAR(p.depth, test::opticalDepth(slab->binding().grids()[0], r.at(a), r.at(b), 3.0),
                0.1);
    EXPECT_EQ(p.at(a - 0.01f), 0.f);
    EXPECT_NEAR(p.at(1.f), 3.f, 1e-5f);  // t = 1: the slab's middle, x = 0.5
}
