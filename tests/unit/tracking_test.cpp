// Transport against closed forms: ratio-tracking transmittance through a homogeneous box, an
// analytic heterogeneous (linear) grid and a scaled transform; delta-tracking free-flight
// distances follow the exponential law (Kolmogorov–Smirnov).
#include "transport/tracking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "film/color.h"
#include "render/renderer.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr int kN = 32;           // voxels per axis, index 0..31
constexpr double kH = 1.0 / 32;  // voxel size, m

std::unique_ptr<Medium> makeMedium(const std::function<float(int, int, int)>& f, float sigmaA,
                                   float sigmaS, const Transform& xf = Transform()) {
    return test::gridMedium(f, 0, kN - 1, kH, sigmaA, sigmaS, 0.f, xf);
}

struct Estimate {
    double mean, stderr_;
};

Estimate estimateT(const Medium& m, const Ray& r, float tMax, int n, SamplerKind kind) {
    TrackingContext ctx({&m});
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        Sampler s = test::pathSampler(kind, 3, uint64_t(i));
        ctx.setWavelengths(SampledWavelengths::sampleVisible(s.get1D()));
        double T = transmittance(ctx, r, tMax, s)[0];
        sum += T;
        sum2 += T * T;
    }
    double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

}  // namespace

TEST(Tracking, HomogeneousBoxTransmittanceMatchesBeerLambert) {
    const float sigma = 4.f;
    auto m = makeMedium([](int, int, int) { return 1.f; }, 1.f, sigma - 1.f);
    // Interior of the active region, where trilinear interpolation of a constant is exact.
    Vec3 a(float(2 * kH), float(5 * kH), float(7 * kH)),
        b(float(29 * kH), float(5 * kH), float(7 * kH));
    float L = length(b - a);
    for (SamplerKind kind : test::kSamplerKinds) {
        Estimate e = estimateT(*m, Ray{a, normalize(b - a), L}, L, 20000, kind);
        double exact = std::exp(-sigma * L);
        EXPECT_NEAR(e.mean, exact, 4 * e.stderr_ + 1e-6) << "exact " << exact;
        EXPECT_GT(e.stderr_, 0.0);  // ratio tracking with RR is a random estimator
    }
}

TEST(Tracking, LinearRampTransmittanceMatchesClosedForm) {
    // density(x) = 0.5 + i/31 along x: trilinear reproduces the linear function exactly, so
    // τ = σ ∫ (0.5 + x/(31 h)) dx in closed form.
    const float sigma = 3.f;
    auto m = makeMedium([](int i, int, int) { return 0.5f + float(i) / 31.f; }, 0.f, sigma);
    double x0 = 1.5 * kH, x1 = 30.0 * kH;
    Vec3 a(float(x0), float(9 * kH), float(9 * kH));
    float L = float(x1 - x0);
    auto F = [](double x) { return 0.5 * x + x * x / (2.0 * 31.0 * kH); };
    double exact = std::exp(-sigma * (F(x1) - F(x0)));
    for (SamplerKind kind : test::kSamplerKinds) {
        Estimate e = estimateT(*m, Ray{a, Vec3(1, 0, 0), L}, L, 20000, kind);
        EXPECT_NEAR(e.mean, exact, 4 * e.stderr_ + 1e-6) << "exact " << exact;
    }
}

TEST(Tracking, ThinAndThickCellsTogetherMatchTheOpticalDepth) {
    // Thin smoke (density 0.1, σ̄ℓ ≈ 0.1 per majorant cell of 1/16 m: plain ratio tracking,
    // no control) around a dense sheet two voxels thick (σ̄ℓ ≈ 1.4: a control at the cell's
    // middle), crossed along x: residual ratio tracking switches per cell (kThinCell in
    // transport/tracking.cpp) and must stay unbiased across the switch, and spend fewer lookups
    // than one control per cell would.
    const float sigma = 22.f;
    auto m = makeMedium([](int i, int, int) { return i == 15 || i == 16 ? 1.f : 0.1f; }, 2.f,
                        sigma - 2.f);
    const Vec3 a(float(1.5 * kH), float(9 * kH), float(9 * kH)), b(float(30 * kH), a.y, a.z);
    const float L = length(b - a);
    const FloatGrid& grid = m->binding().grids()[0];
    const double exact = std::exp(-test::opticalDepth(grid, a, b, sigma));
    for (SamplerKind kind : test::kSamplerKinds) {
        Estimate e = estimateT(*m, Ray{a, Vec3(1, 0, 0), L}, L, 20000, kind);
        EXPECT_NEAR(e.mean, exact, 4 * e.stderr_ + 1e-6) << "exact " << exact;
    }
    // One control per majorant cell the ray crosses would spend `cells` lookups per ray before
    // any residual collision.
    int cells = 0;
    m->majorant().traverse(a, Vec3(1, 0, 0), 0.f, L, [&](float, float, float sigmaMaj) {
        cells += sigmaMaj > 0.f;
        return true;
    });
    TrackingContext ctx({m.get()});
    const int n = 2000;
    for (int i = 0; i < n; ++i) {
        Sampler s(5, uint64_t(i), 0);
        ctx.setWavelengths(SampledWavelengths::sampleVisible(s.get1D()));
        transmittance(ctx, Ray{a, Vec3(1, 0, 0), L}, L, s);
    }
    std::printf("%d cells; %.2f lookups per ray\n", cells, double(ctx.lookups) / n);
    EXPECT_LT(double(ctx.lookups) / n, 0.6 * cells);
}

TEST(Tracking, ScaledTransformStretchesOpticalDepth) {
    // σ is per world metre: scaling the object by 2 doubles every path length inside it.
    const float sigma = 2.f;
    auto m =
        makeMedium([](int, int, int) { return 1.f; }, sigma, 0.f, Transform::scale(Vec3d(2.0)));
    Vec3 a(float(2 * 2 * kH), float(10 * 2 * kH), float(10 * 2 * kH));
    float L = float(2 * 25 * kH);
    for (SamplerKind kind : test::kSamplerKinds) {
        Estimate e = estimateT(*m, Ray{a, Vec3(1, 0, 0), L}, L, 20000, kind);
        EXPECT_NEAR(e.mean, std::exp(-sigma * L), 4 * e.stderr_ + 1e-6);
    }
}

TEST(Tracking, TransmittanceOutsideMediumIsOne) {
    auto m = makeMedium([](int, int, int) { return 1.f; }, 1.f, 1.f);
    Estimate e =
        estimateT(*m, Ray{Vec3(-1, -1, -1), Vec3(0, 1, 0), 10.f}, 10.f, 100, SamplerKind::Sobol);
    EXPECT_EQ(e.mean, 1.0);
}

TEST(Tracking, FreeFlightDistancesAreExponential) {
    // A pure absorber: the first real collision distance has the truncated exponential CDF
    // F(t) = (1 − e^{−σt}) / (1 − e^{−σL}). Kolmogorov–Smirnov at α = 0.001.
    const float sigma = 5.f;
    auto m = makeMedium([](int, int, int) { return 1.f; }, sigma, 0.f);
    TrackingContext ctx({m.get()});
    Vec3 a(float(2 * kH), float(16 * kH), float(16 * kH));
    const float L = float(27 * kH);
    Ray r{a, Vec3(1, 0, 0), L};
    std::vector<double> t;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Sampler s(5, uint64_t(i), 0);
        ctx.setWavelengths(SampledWavelengths::sampleVisible(s.get1D()));
        trackCollisions(ctx, r, L, s, [&](const Collision& c) {
            EventProbabilities e = eventProbabilities(c);
            if (s.get1D() < e.pAbsorb + e.pScatter) {
                t.push_back(c.t);
                return Track::Stop;
            }
            return Track::Continue;
        });
    }
    // The fraction that escaped must be e^{−σL} (binomial, 4σ).
    double pEscape = std::exp(-sigma * L);
    double escaped = double(n - int(t.size())) / n;
    EXPECT_NEAR(escaped, pEscape, 4 * std::sqrt(pEscape * (1 - pEscape) / n));
    std::sort(t.begin(), t.end());
    double norm = 1.0 - std::exp(-sigma * L), d = 0.0;
    for (size_t i = 0; i < t.size(); ++i) {
        double F = (1.0 - std::exp(-sigma * t[i])) / norm;
        d = std::max(
            {d, std::abs(F - double(i) / t.size()), std::abs(F - double(i + 1) / t.size())});
    }
    EXPECT_LT(d, 1.95 / std::sqrt(double(t.size())));  // KS critical value at α = 0.001
}

TEST(Tracking, SpectralTrackingWeightsAreUnbiasedAtEveryWavelength) {
    // Delta tracking with the history-aware event probabilities of eventProbabilities(c, β)
    // (Kutz et al. 2017) through 5 m of a strongly spectral homogeneous medium (σa from
    // 0.05 1/m at 360 nm to 3 1/m at 830 nm, like water; σs = 0.1 1/m): a path that neither
    // absorbs nor scatters carries β_i = T(λ_i) in expectation at each of its wavelengths.
    ShaderDesc s;
    s.name = "spectral";
    MediumComponent c;
    c.sigmaA = Spectrum::fromTable({360.f, 830.f}, {0.05f, 3.f});
    c.sigmaS = Spectrum(0.1f);
    s.components = {c};
    Bounds3 box;
    box.expand(Vec3(0.f));
    box.expand(Vec3(5.f, 1.f, 1.f));
    Medium m(s, box, Transform(), 1.f);
    TrackingContext ctx({&m});
    SampledWavelengths w;
    w.lambda = {400.f, 480.f, 560.f, 640.f};
    w.pdf.fill(1.f);
    ctx.setWavelengths(w);
    const Ray ray{Vec3(0.f, 0.5f, 0.5f), Vec3(1.f, 0.f, 0.f), kInfinity};
    const int n = 200000;
    double sum[4] = {}, sum2[4] = {};
    for (int i = 0; i < n; ++i) {
        Sampler sampler(19, uint64_t(i), 0);
        SampledSpectrum beta(1.f);
        trackCollisions(ctx, ray, 5.f, sampler, [&](const Collision& col) {
            EventProbabilities e = eventProbabilities(col, beta);
            if (sampler.get1D() < e.pAbsorb + e.pScatter) {
                beta = SampledSpectrum(0.f);
                return Track::Stop;
            }
            beta *= e.sigmaN / (col.sigmaMaj * e.pNull);
            return Track::Continue;
        });
        for (int k = 0; k < 4; ++k) {
            sum[k] += beta[k];
            sum2[k] += double(beta[k]) * beta[k];
        }
    }
    for (int k = 0; k < 4; ++k) {
        double mean = sum[k] / n, se = std::sqrt(std::max(0.0, sum2[k] / n - mean * mean) / n);
        double expected = std::exp(-5.0 * (c.sigmaA(w.lambda[size_t(k)]) + 0.1));
        EXPECT_NEAR(mean, expected, 4 * se + 1e-4) << w.lambda[size_t(k)] << " nm";
        // Bounded weights: the blue wavelength's estimate is not a rare huge β.
        EXPECT_LT(se, 0.02 + 0.05 * expected) << w.lambda[size_t(k)] << " nm";
    }
}

namespace {

// `count` grid media: count − 1 thin boxes off the ray (a row along z from z = 2 m), then one
// dense box (σa = 3/m) on the ray, last in the context.
std::vector<std::unique_ptr<Medium>> boxesLastDense(int count) {
    std::vector<std::unique_ptr<Medium>> media;
    for (int i = 0; i + 1 < count; ++i)
        media.push_back(makeMedium([](int, int, int) { return 1.f; }, 0.1f, 0.f,
                                   Transform::translate(Vec3d(0.0, 0.0, 2.0 + 1.5 * i))));
    media.push_back(makeMedium([](int, int, int) { return 1.f; }, 3.f, 0.f));
    return media;
}

}  // namespace

TEST(Tracking, EveryVolumeOfManyIsTracked) {
    // The last of 33 (and of 300) volumes is as opaque to ratio tracking and to delta tracking
    // as it is alone: T = e^{−σL} through it, and the fraction of free flights that collide
    // in it is 1 − e^{−σL}.
    for (int count : {33, 300}) {
        auto media = boxesLastDense(count);
        std::vector<const Medium*> ptrs;
        for (auto& m : media) ptrs.push_back(m.get());
        TrackingContext ctx(ptrs);
        Vec3 a(float(2 * kH), float(16 * kH), float(16 * kH));
        const float L = float(27 * kH);
        const Ray r{a, Vec3(1, 0, 0), L};
        const double exact = std::exp(-3.0 * L);
        const int n = 4000;
        double sumT = 0, sumT2 = 0;
        int collided = 0, lastMedium = 0;
        for (int i = 0; i < n; ++i) {
            Sampler s(23, uint64_t(i), 0);
            ctx.setWavelengths(SampledWavelengths::sampleVisible(s.get1D()));
            const double T = transmittance(ctx, r, L, s)[0];
            sumT += T;
            sumT2 += T * T;
            trackCollisions(ctx, r, L, s, [&](const Collision& c) {
                if (s.get1D() < eventProbabilities(c).pAbsorb) {
                    ++collided;
                    lastMedium += c.medium == count - 1;
                    return Track::Stop;
                }
                return Track::Continue;
            });
        }
        const double mean = sumT / n;
        const double se = std::sqrt(std::max(0.0, sumT2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, exact, 4 * se + 1e-4) << count << " volumes";
        const double p = 1.0 - exact;
        EXPECT_NEAR(double(collided) / n, p, 4 * std::sqrt(p * (1 - p) / n)) << count;
        EXPECT_EQ(lastMedium, collided) << count << " volumes";
    }
}

TEST(Tracking, ThreeHundredVolumesRenderAsTheOneThatShows) {
    // A dense smoke box lit from above, seen from the front; then the same with 299 thin boxes
    // first in the list, off-screen and out of the light's way (below the floor of the view).
    // The single-scatter images agree per colour channel within their noise (~1 % on the mean:
    // the first at 1024 samples, the second at 256); with the last volume dropped the second
    // would be empty.
    auto scene = [](int count) {
        RenderScene s;
        for (int i = 0; i + 1 < count; ++i)
            s.media.push_back(makeMedium(
                [](int, int, int) { return 1.f; }, 0.1f, 0.f,
                Transform::translate(Vec3d(1.5 * (i % 20), -10.0 - 1.5 * (i / 20), 0.0))));
        s.media.push_back(makeMedium([](int, int, int) { return 1.f; }, 0.5f, 3.f));
        s.lights.push_back(makeDistantLight(Vec3(0.f, -1.f, 0.f), 1000.f, Spectrum(1.f)));
        s.camera.position = Vec3(0.5f, 0.5f, 3.f);
        s.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
        s.camera.fovDeg = 30.f;
        return s;
    };
    ColorPipeline color;
    auto single = makeSingleScatterIntegrator();
    const Image one = render(scene(1), *single, test::smallRenderSettings(1024, 3, 16, 16), nullptr)
                          .develop(color);
    const Image many =
        render(scene(300), *single, test::smallRenderSettings(256, 4, 16, 16), nullptr)
            .develop(color);
    const test::ImageError e = test::compareImages(many, one);
    std::printf("300 volumes against the one that shows: bias R %+.4f G %+.4f B %+.4f\n",
                e.channelBias[0], e.channelBias[1], e.channelBias[2]);
    EXPECT_LT(std::abs(e.bias), 0.03);
}
