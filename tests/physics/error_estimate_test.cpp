// The film's error estimate (film/film_error.h, what --noise-threshold stops on) against the
// error measured against a converged render of the same integrator, on the fog box
// (fog_box_scene.h), for the two samplers and two integrators. The estimate is the per-sample
// variance over n: exact in expectation for independent samples of a light-tailed estimator
// (single scattering, random sampler), but
//  - a stratified sampler (Sobol) converges faster than 1/n, so the estimate is an upper bound
//    by no fixed factor: the smoother the integrand, the larger (single scattering at 16 spp:
//    ~10 × on this uniform fog, ~2.5 × on the heterogeneous box of tests/unit/passes_test.cpp);
//  - a heavy-tailed estimator (volpath: rare bright paths) reads low at few samples: the
//    bright sample a pixel has not drawn yet is in neither its variance nor its error, and a
//    pixel that has drawn one divides by its own inflated mean (m² in the denominator). The
//    shortfall closes as samples grow (here 0.86 × at 16 spp and 1.06 × at 64; on the
//    heterogeneous box 0.3 × at 4 spp, 0.6 × at 16, 0.9 × at 64).
// These are the factors docs/performance.md states; the test holds them with margin.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "film/film_error.h"
#include "fog_box_scene.h"
#include "render/renderer.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr int kSize = 32;

// The measured relMSE of `image` against `reference` in the estimator's terms (CIE XYZ, the
// covered pixels, ε = 10⁻³ · the mean of the reference's channel means, squared), less the
// reference's own variance of the mean, which the difference carries too.
double measuredRelMse(const Film& image, const Film& reference, const FilmError& estimate) {
    double meanRef = 0;
    size_t n = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (estimate.pixelError[size_t(y) * kSize + x] > 0)
                for (int c = 0; c < 3; ++c, ++n)
                    meanRef += reference.pixel(x, y).xyz[c] / reference.pixel(x, y).samples;
    const double eps = 1e-3 * std::pow(meanRef / double(n), 2.0);
    double sum = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!(estimate.pixelError[size_t(y) * kSize + x] > 0)) continue;
            const Film::Pixel &p = image.pixel(x, y), &q = reference.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const double m = p.xyz[c] / p.samples, r = q.xyz[c] / q.samples;
                sum += ((m - r) * (m - r) - varianceOfMean(q, c)) / (r * r + eps);
            }
        }
    return sum / double(n);
}

// The estimate over the measured relMSE, averaged over two seeds.
double estimateOverMeasured(const RenderScene& scene, Integrator& integrator, const Film& reference,
                            SamplerKind kind, int spp) {
    double ratio = 0;
    for (uint64_t seed : {3u, 5u}) {
        RenderSettings s = test::smallRenderSettings(spp, seed, kSize, kSize);
        s.sampler = kind;
        const Film image = render(scene, integrator, s, nullptr);
        const FilmError estimate = estimateFilmError(image);
        const double measured = measuredRelMse(image, reference, estimate);
        std::printf("  %s, %d spp, seed %llu: estimated relMSE %.4g, measured %.4g (× %.3f)\n",
                    kind == SamplerKind::Sobol ? "sobol" : "random", spp, (unsigned long long)seed,
                    estimate.relMse, measured, estimate.relMse / measured);
        ratio += 0.5 * estimate.relMse / measured;
    }
    return ratio;
}

// 512 spp: a sixteenth (volpath at 64 spp) to a 32nd (16 spp) of the compared image's
// variance, which measuredRelMse subtracts, and a relative variance per pixel ≤ 0.004 (volpath:
// 0.13 at 16 spp), which biases 1/r² by ≤ 1.2 %: a twentieth of the narrowest margin of the
// factors asserted below (measured 0.98–1.04 against > 0.75). 1024 spp (≤ 0.6 %) took 86–94 %
// of each test's samples.
Film converged(const RenderScene& scene, Integrator& integrator) {
    RenderSettings s = test::smallRenderSettings(512, 1, kSize, kSize);
    s.sampler = SamplerKind::Random;
    return render(scene, integrator, s, nullptr);
}

}  // namespace

TEST(ErrorEstimate, SingleScatteringWithinStatedFactors) {
    const RenderScene scene = test::fogBoxScene();
    auto single = makeSingleScatterIntegrator();
    const Film reference = converged(scene, *single);
    // Independent samples of a light-tailed estimator: the estimate is the error.
    const double random = estimateOverMeasured(scene, *single, reference, SamplerKind::Random, 16);
    EXPECT_GT(random, 0.75);
    EXPECT_LT(random, 1.33);
    // Sobol: an upper bound, by the gain of its stratification (× 10.7 measured).
    const double sobol = estimateOverMeasured(scene, *single, reference, SamplerKind::Sobol, 16);
    EXPECT_GT(sobol, 1.2);
}

TEST(ErrorEstimate, VolPathReadsLowAtFewSamplesAndClosesIn) {
    const RenderScene scene = test::fogBoxScene();
    auto volpath = makeVolPathIntegrator();
    const Film reference = converged(scene, *volpath);
    const double at16 = estimateOverMeasured(scene, *volpath, reference, SamplerKind::Sobol, 16);
    const double at64 = estimateOverMeasured(scene, *volpath, reference, SamplerKind::Sobol, 64);
    EXPECT_GT(at16, 0.5);  // measured 0.86
    EXPECT_LT(at16, 1.5);
    EXPECT_GT(at64, 0.6);  // measured 1.06
    EXPECT_LT(at64, 1.6);
}
