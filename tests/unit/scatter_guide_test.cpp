// The light guide of single scattering's points (transport/scatter_guide.h,
// render/scatter_guide_build.h): points drawn by any guide keep their expectation, the guided
// integrator matches the quadrature of the single-scattering integral, and the guide built for
// a frame follows the light, is interpolated smoothly, is sized to the frame and is the same
// for any thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <utility>
#include <vector>

#include "render/renderer.h"
#include "render/scatter_guide_build.h"
#include "test_support.h"
#include "transport/scatter_point.h"
#include "volume/grid_lookup.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;

// A 32³ box of voxels kH wide, density(i, j, k), lit straight down (−y) by a white sun.
RenderScene litBox(float (*density)(int, int, int), float sigmaA, float sigmaS) {
    RenderScene scene;
    scene.media.push_back(test::gridMedium(density, 0, 31, kH, sigmaA, sigmaS, 0.f));
    scene.lights.push_back(makeDistantLight(Vec3(0, -1, 0), 470.f, Spectrum(1.f)));
    return scene;
}

// The mean of x(i) over i < n and its standard error.
template <typename F>
std::pair<double, double> meanAndError(int n, F&& x) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const double v = x(i);
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n;
    return {mean, std::sqrt((sum2 / n - mean * mean) / n)};
}

}  // namespace

TEST(ScatterGuide, GuidedScatteringPointsKeepTheirExpectation) {
    // Points drawn ∝ T σs g with a wild guide g (values spread over two decades, cell by cell)
    // and weighted by 1/g: E[Σ_k weight_k f(t_k)] = ∫ T σs f dt for any f, here f(t) = 1 + 4t
    // along a ray through the box, against the midpoint rule on the grid's own field.
    const float sa = 0.5f, ss = 2.f;
    const RenderScene scene = litBox([](int, int, int) { return 1.f; }, sa, ss);
    const FloatGrid& g = scene.media[0]->binding().grids()[0];
    auto acc = g.accessor();
    const Ray ray{Vec3(-0.2f, 0.3f, 0.6f), Vec3(1, 0, 0), kInfinity};
    auto f = [](double t) { return 1.0 + 4.0 * t; };
    double expected = 0.0, tau = 0.0;
    const int n = 4000;
    const double dt = 1.5 / n;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) * dt, density = g.sample(acc, ray.at(float(t)));
        expected += std::exp(-tau) * ss * density * f(t) * dt;
        tau += (sa + ss) * density * dt;
    }
    constexpr int r = 32;
    std::vector<float> values(size_t(r) * r * r);
    for (size_t i = 0; i < values.size(); ++i)
        values[i] = std::pow(10.f, -2.f * float(mix64(i) >> 40) * 0x1p-24f);
    const ScatterGuide guide(Bounds3{Vec3(0.f), Vec3(1.f)}, r, std::move(values), 1e-3f);

    ThreadState ts(scene);
    for (const ScatterGuide* gd : {static_cast<const ScatterGuide*>(nullptr), &guide}) {
        SCOPED_TRACE(gd ? "guided" : "unguided");
        const auto [mean, se] = meanAndError(40000, [&](int i) {
            Sampler s(SamplerKind::Random, 5, 0, uint64_t(i));
            ts.tracking.setWavelengths(SampledWavelengths::sampleVisible(s.get1D()));
            SampledSpectrum L(0.f);
            const ScatterPointWalk walk =
                chooseScatterPoints(ts.tracking, ray, kInfinity, s,
                                    EmissionSink{SampledSpectrum(1.f), &L}, nullptr, gd);
            double x = 0.0;
            for (int k = 0; walk.chosen && k < kScatterPoints; ++k)
                x += walk.weight[k][0] * f(walk.collision[k].t);
            return x;
        });
        EXPECT_NEAR(mean, expected, 4 * se) << "expected " << expected << " ± " << se;
    }
}

TEST(ScatterGuide, GuidedRenderMatchesTheQuadrature) {
    // The whole integrator with the guide its preprocess builds for a frame of 2²⁰ samples
    // (32³ cells): the pixel's mean against the quadrature of the single-scattering integral,
    // light from the top through a box whose density falls with height, so that the guide
    // varies along the ray.
    const float sa = 0.5f, ss = 2.f, E = 470.f;
    const RenderScene scene =
        litBox([](int, int j, int) { return 0.2f + 0.05f * float(j); }, sa, ss);
    const FloatGrid& g = scene.media[0]->binding().grids()[0];
    auto acc = g.accessor();
    // A ray climbing through the box: its points see the light through less and less smoke.
    const Ray ray{Vec3(-0.2f, 0.05f, 0.5f), normalize(Vec3(1.f, 0.6f, 0.f)), kInfinity};
    double expected = 0.0, tauCam = 0.0;
    const int n = 4000;
    const double dt = 2.0 / n;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) * dt;
        const Vec3 p = ray.at(float(t));
        const double density = g.sample(acc, p);
        if (density > 0) {
            const double Tl = std::exp(-test::opticalDepth(g, p, Vec3(p.x, 1.2f, p.z), sa + ss));
            expected += std::exp(-tauCam) * ss * density / (4 * M_PI) * (E / 470.0) * Tl * dt;
        }
        tauCam += (sa + ss) * density * dt;
    }
    ASSERT_TRUE(buildScatterGuide(scene, uint64_t(1) << 20));
    auto integrator = makeSingleScatterIntegrator();
    integrator->preprocess(scene, uint64_t(1) << 20);
    ThreadState ts(scene);
    const auto [mean, se] = meanAndError(40000, [&](int i) {
        Sampler s(SamplerKind::Sobol, 1, 0, uint64_t(i));
        SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        return double(integrator->Li(scene, ray, w, s, ts).L[0]);
    });
    EXPECT_NEAR(mean, expected, 4 * se) << "expected " << expected << " ± " << se;
}

TEST(ScatterGuide, FollowsTheLightThroughTheSmoke) {
    // Constant density lit from the top: the guess falls with depth as Beer–Lambert says,
    // exp(−σt Δy) between two heights (within the coarse march's error).
    const float sa = 1.f, ss = 4.f;
    const RenderScene scene = litBox([](int, int, int) { return 1.f; }, sa, ss);
    const auto guide = buildScatterGuide(scene, uint64_t(1) << 20);
    ASSERT_TRUE(guide);
    EXPECT_EQ(guide->resolution(), 32);
    // Both above the floor (T > 0.05 from the top at y ≈ 1).
    const float top = guide->at(Vec3(0.5f, 0.9f, 0.5f)), low = guide->at(Vec3(0.5f, 0.6f, 0.5f));
    EXPECT_GT(top, low);
    EXPECT_NEAR(std::log(top / low), (sa + ss) * 0.3, 0.1 * (sa + ss) * 0.3);
    // Deep enough (T ~ 0.01), the floor holds: 5 % of the brightest cell, the top one, whose
    // value is within a cell's exp(σt h) ≈ 1.17 of the guess a little below it.
    const float bottom = guide->at(Vec3(0.5f, 0.02f, 0.5f));
    EXPECT_NEAR(bottom / guide->at(Vec3(0.5f, 0.95f, 0.5f)), 0.05f, 0.01f);
}

TEST(ScatterGuide, InterpolatesBetweenCellCentres) {
    // Values linear in x along the cells' centres give g linear in x between the first and last
    // centre, and the border values beyond them.
    constexpr int r = 4;
    std::vector<float> values(size_t(r) * r * r);
    for (int k = 0; k < r; ++k)
        for (int j = 0; j < r; ++j)
            for (int i = 0; i < r; ++i) values[size_t((k * r + j) * r + i)] = 1.f + float(i);
    const ScatterGuide guide(Bounds3{Vec3(0.f), Vec3(4.f)}, r, std::move(values), 0.01f);
    EXPECT_FLOAT_EQ(guide.at(Vec3(0.5f, 2.f, 2.f)), 1.f);
    EXPECT_FLOAT_EQ(guide.at(Vec3(1.75f, 0.3f, 3.9f)), 2.25f);
    EXPECT_FLOAT_EQ(guide.at(Vec3(3.5f, 2.f, 2.f)), 4.f);
    EXPECT_FLOAT_EQ(guide.at(Vec3(-7.f, 2.f, 2.f)), 1.f);
    EXPECT_FLOAT_EQ(guide.at(Vec3(9.f, 2.f, 2.f)), 4.f);
    EXPECT_FLOAT_EQ(guide.at(Vec3(NAN, 2.f, 2.f)), 1.f);
}

TEST(ScatterGuide, SizedToTheFrameAndTheSameForAnyThreadCount) {
    EXPECT_EQ(scatterGuideResolution(0), 0);                   // unknown frame: no guide
    EXPECT_EQ(scatterGuideResolution(64), 4);                  // the smallest
    EXPECT_EQ(scatterGuideResolution(48 * 27 * 4), 8);         // a test's small frame
    EXPECT_EQ(scatterGuideResolution(256 * 256 * 4), 32);      // the race at 4 spp
    EXPECT_EQ(scatterGuideResolution(uint64_t(1) << 40), 32);  // the largest
    const RenderScene scene =
        litBox([](int i, int j, int k) { return float((i * 7 + j * 3 + k) % 5) * 0.3f; }, 1.f, 3.f);
    EXPECT_FALSE(buildScatterGuide(scene, 0));
    std::vector<float> one, two;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        const auto guide = buildScatterGuide(scene, uint64_t(1) << 20);
        ASSERT_TRUE(guide);
        std::vector<float>& v = threads == 1 ? one : two;
        for (int i = 0; i < 1000; ++i)
            v.push_back(guide->at(
                Vec3(float(mix64(uint64_t(i)) >> 40) * 0x1p-24f, 0.1f * float(i % 10), 0.37f)));
    }
    EXPECT_EQ(one, two);
}
