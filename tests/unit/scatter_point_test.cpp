// Single scattering's walk along the camera ray (transport/scatter_point.h): its transmittance
// and its scattering points keep their expectations — the closed forms of the grid's own field
// by quadrature — through smoke whose density changes along the ray, in one medium and in two
// superposed.
#include "transport/scatter_point.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "render/integrator.h"
#include "test_support.h"
#include "volume/grid_lookup.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;
const Ray kRay{Vec3(-0.2f, 0.4f, 0.55f), Vec3(1, 0, 0), kInfinity};

// Density rising and falling along x, from 0.05 to 2.05.
float wavy(int i, int, int) { return 0.05f + 2.f * float(std::pow(std::sin(0.2 * i), 2)); }

// Along kRay through the media: the optical depth ∫ σt and ∫ T σs f dt by the midpoint rule
// on the grids' own trilinear fields.
struct Quadrature {
    double tau = 0.0, scattered = 0.0;
};
template <typename F>
Quadrature quadrature(const RenderScene& scene, const float (&sigmaT)[2], const float (&sigmaS)[2],
                      F&& f) {
    Quadrature q;
    const int n = 6000;
    const double dt = 1.5 / n;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) * dt;
        double st = 0.0, ss = 0.0;
        for (size_t m = 0; m < scene.media.size(); ++m) {
            const FloatGrid& g = scene.media[m]->binding().grids()[0];
            auto acc = g.accessor();
            const double d = g.sample(acc, kRay.at(float(t)));
            st += sigmaT[m] * d;
            ss += sigmaS[m] * d;
        }
        q.scattered += std::exp(-q.tau - 0.5 * st * dt) * ss * f(t) * dt;
        q.tau += st * dt;
    }
    return q;
}

struct Moments {
    double mean, se;
};
template <typename F>
Moments moments(int n, F&& x) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        const double v = x(i);
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n, var = std::max(0.0, sum2 / n - mean * mean);
    return {mean, std::sqrt(var / n)};
}

void expectWalkExpectations(const RenderScene& scene, const float (&sigmaT)[2],
                            const float (&sigmaS)[2]) {
    auto f = [](double t) { return 1.0 + 4.0 * t; };
    const Quadrature q = quadrature(scene, sigmaT, sigmaS, f);
    ThreadState ts(scene);
    for (SamplerKind kind : test::kSamplerKinds) {
        SCOPED_TRACE(kind == SamplerKind::Sobol ? "sobol" : "random");
        double sumT = 0, sumT2 = 0;
        const int n = 40000;
        const Moments points = moments(n, [&](int i) {
            Sampler s = test::pathSampler(kind, 3, uint64_t(i));
            ts.tracking.setWavelengths(SampledWavelengths::sampleVisible(s.get1D()));
            SampledSpectrum L(0.f);
            const ScatterPointWalk walk = chooseScatterPoints(
                ts.tracking, kRay, kInfinity, s, EmissionSink{SampledSpectrum(1.f), &L});
            sumT += walk.T[0];
            sumT2 += double(walk.T[0]) * walk.T[0];
            double x = 0.0;
            for (int k = 0; walk.chosen && k < kScatterPoints; ++k)
                x += walk.weight[k][0] * f(walk.collision[k].t);
            return x;
        });
        EXPECT_NEAR(points.mean, q.scattered, 4 * points.se + 1e-3 * q.scattered)
            << "∫ T σs f: expected " << q.scattered << " ± " << points.se;
        const double meanT = sumT / n, seT = std::sqrt((sumT2 / n - meanT * meanT) / n);
        EXPECT_NEAR(meanT, std::exp(-q.tau), 4 * seT + 1e-3 * std::exp(-q.tau))
            << "T: expected " << std::exp(-q.tau) << " ± " << seT;
    }
}

}  // namespace

TEST(ScatterPointWalk, OneMediumKeepsItsExpectations) {
    RenderScene scene;
    scene.media.push_back(test::gridMedium(wavy, 0, 31, kH, 0.3f, 1.2f));
    expectWalkExpectations(scene, {1.5f, 0.f}, {1.2f, 0.f});
}

TEST(ScatterPointWalk, TwoMediaKeepTheirExpectations) {
    RenderScene scene;
    scene.media.push_back(test::gridMedium(wavy, 0, 31, kH, 0.3f, 1.2f));
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 0.5f; }, 0, 31, kH, 0.1f, 0.4f));
    expectWalkExpectations(scene, {1.5f, 0.5f}, {1.2f, 0.4f});
}
