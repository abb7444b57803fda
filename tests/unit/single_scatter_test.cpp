// The single-scattering integrator against an independent quadrature of the single-scattering
// integral on the same grid, and the render pass's determinism across thread counts.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "film/color.h"
#include "render/renderer.h"
#include "test_support.h"
#include "volume/grid_lookup.h"

using namespace mirage;

namespace {

constexpr double kH = 1.0 / 32;

RenderScene boxScene(float sigmaA, float sigmaS, float g, float irradiance) {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, sigmaA, sigmaS, g));
    // Light travels straight down (−y).
    scene.lights.push_back(makeDistantLight(Vec3(0, -1, 0), irradiance, Spectrum(1.f)));
    scene.camera.position = Vec3(0.5f, 0.5f, 3.f);
    scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
    return scene;
}

}  // namespace

TEST(SingleScatter, MatchesQuadratureOfTheSingleScatteringIntegral) {
    const float sa = 0.5f, ss = 2.f, E = 470.f;  // E/470 nm = 1 W·m⁻²·nm⁻¹ per nm
    RenderScene scene = boxScene(sa, ss, 0.f, E);
    const Medium& m = *scene.media[0];
    const FloatGrid& g = m.binding().grids()[0];
    auto acc = g.accessor();

    // Camera ray along +x through the box at y = z = 16 h; light from the top, isotropic phase.
    Vec3 o(-0.2f, float(16 * kH), float(16 * kH));
    Ray ray{o, Vec3(1, 0, 0), kInfinity};
    const int n = 4000;
    double expected = 0.0, tauCam = 0.0;
    const double t0 = 0.0, t1 = 1.5, dt = (t1 - t0) / n;
    for (int i = 0; i < n; ++i) {
        double t = t0 + (i + 0.5) * dt;
        Vec3 p = ray.at(float(t));
        double density = g.sample(acc, p);
        if (density > 0) {
            double Tl = std::exp(-test::opticalDepth(g, p, Vec3(p.x, 1.2f, p.z), sa + ss));
            expected += std::exp(-tauCam) * ss * density * (1.0 / (4 * M_PI)) * 1.0 * Tl * dt;
        }
        tauCam += (sa + ss) * density * dt;
    }

    auto integrator = makeSingleScatterIntegrator();
    ThreadState ts(scene);
    for (SamplerKind kind : test::kSamplerKinds) {
        SCOPED_TRACE(kind == SamplerKind::Sobol ? "sobol" : "random");
        double sum = 0, sum2 = 0, alpha = 0;
        const int samples = 40000;
        for (int i = 0; i < samples; ++i) {
            Sampler s(kind, 1, 0, uint64_t(i));
            SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
            ts.tracking.setWavelengths(w);
            RadianceSample r = integrator->Li(scene, ray, w, s, ts);
            for (int k = 1; k < kSpectrumSamples; ++k) ASSERT_EQ(r.L[k], r.L[0]);  // grey medium
            sum += r.L[0];
            sum2 += double(r.L[0]) * r.L[0];
            alpha += r.alpha;
        }
        double mean = sum / samples;
        double se = std::sqrt((sum2 / samples - mean * mean) / samples);
        EXPECT_NEAR(mean, expected, 4 * se) << "expected " << expected << " ± " << se;
        EXPECT_NEAR(alpha / samples, 1.0 - std::exp(-tauCam), 0.01);
    }
}

TEST(SingleScatter, EmptyRayIsBlackAndTransparent) {
    RenderScene scene = boxScene(0.5f, 2.f, 0.f, 470.f);
    auto integrator = makeSingleScatterIntegrator();
    ThreadState ts(scene);
    Sampler s(1, 0, 0);
    SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    ts.tracking.setWavelengths(w);
    RadianceSample r =
        integrator->Li(scene, Ray{Vec3(5, 5, 5), Vec3(0, 1, 0), kInfinity}, w, s, ts);
    EXPECT_TRUE(r.L.isZero());
    EXPECT_EQ(r.alpha, 0.f);
}

TEST(Renderer, SameSeedSameBitsForOneAndTwoThreads) {
    RenderScene scene = boxScene(0.5f, 3.f, 0.4f, 1000.f);
    RenderSettings rs;
    rs.width = 48;
    rs.height = 40;
    rs.tileSize = 8;
    rs.spp = 3;
    rs.seed = 42;
    rs.progress = Progress::Mode::Quiet;
    ColorPipeline color;
    auto integrator = makeSingleScatterIntegrator();
    Image images[2];
    for (int threads : {1, 2}) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
        images[threads - 1] = render(scene, *integrator, rs, nullptr).develop(color);
    }
    ASSERT_EQ(images[0].rgba.size(), images[1].rgba.size());
    EXPECT_EQ(0, std::memcmp(images[0].rgba.data(), images[1].rgba.data(),
                             images[0].rgba.size() * sizeof(float)));
    double total = 0;
    for (float v : images[0].rgba) total += v;
    EXPECT_GT(total, 0.0);  // the box is lit and visible
    rs.seed = 43;
    Image other = render(scene, *integrator, rs, nullptr).develop(color);
    EXPECT_NE(0, std::memcmp(images[0].rgba.data(), other.rgba.data(),
                             other.rgba.size() * sizeof(float)));
}
