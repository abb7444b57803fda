// The ocean medium: pure water + chlorophyll grid + CDOM. Its coefficients at a point are the
// published laws (ocean_spectra.h), its majorant bounds σt everywhere at every wavelength
// although chlorophyll absorption is non-linear in concentration, and the water lobe
// normalises and is sampled exactly (χ²).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "core/rng.h"
#include "medium/medium.h"
#include "medium/ocean_components.h"
#include "spectrum/ocean_spectra.h"
#include "test_support.h"
#include "transport/ray_optical_depth.h"

using namespace mirage;

namespace {

constexpr float kCdom440 = 0.05f;  // 1/m
constexpr float kDensityScale = 1.5f;

ShaderDesc oceanShader(float chlScale) {
    ShaderDesc s;
    s.name = "ocean-test";
    MediumComponent water, chl, cdom;
    water.name = "water";
    makeWater(&water);
    chl.name = "chlorophyll";
    chl.grid = "chlorophyll";
    chl.concentration = chlScale;
    makeChlorophyll(&chl);
    cdom.name = "cdom";
    cdom.concentration = kCdom440;
    makeCdom(&cdom, ocean::kCdomSlope);
    s.components = {water, chl, cdom};
    return s;
}

// Chlorophyll varying over three decades: 0.01–10 mg/m³ along x, lumpy in y and z.
float chlorophyllAt(int i, int j, int k) {
    return 0.01f * std::pow(1000.f, i / 31.f) * (1.f + 0.5f * std::sin(0.7f * j + 0.3f * k));
}

std::unique_ptr<Medium> oceanMedium(const std::function<float(int, int, int)>& chl) {
    std::vector<FloatGrid> grids{test::makeGrid(chl, 0, 31, 1.0 / 16, Vec3d(0.0), "chl")};
    return std::make_unique<Medium>(oceanShader(2.f), std::move(grids), Transform(),
                                    kDensityScale, 8);
}

float cellAt(const MajorantGrid& m, const Vec3& p) {
    int c[3];
    const Bounds3& b = m.bounds();
    for (int a = 0; a < 3; ++a) {
        float x = (p[a] - b.lo[a]) / (b.hi[a] - b.lo[a]) * float(m.res(a));
        c[a] = clamp(int(std::floor(x)), 0, m.res(a) - 1);
    }
    return m.cell(c[0], c[1], c[2]);
}

}  // namespace

TEST(OceanMedium, CoefficientsAtAPointAreThePublishedLaws) {
    const float chlGrid = 0.8f;  // a uniform grid, so any interior point reads it exactly
    auto m = oceanMedium([&](int, int, int) { return chlGrid; });
    Medium::Context ctx(*m);
    Sampler s(3, 0, 0);
    for (int trial = 0; trial < 50; ++trial) {
        SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ctx.setWavelengths(w);
        MediumPoint mp;
        m->eval(Vec3(1.f, 1.f, 1.f), ctx, &mp);
        const float C = chlGrid * 2.f * kDensityScale;  // mg/m³
        for (int j = 0; j < kSpectrumSamples; ++j) {
            float l = w.lambda[j];
            double aw = kDensityScale * ocean::waterAbsorption()(l);
            double aph = ocean::bricaudA()(l) * std::pow(C, 1.0 - ocean::bricaudB()(l));
            double ay = kDensityScale * kCdom440 * std::exp(-0.014 * (l - 440.0));
            double bw = kDensityScale * 0.00288 * std::pow(l / 500.0, -4.32);
            double bp = 0.30 * std::pow(C, 0.62) * 550.0 / l;
            EXPECT_NEAR(mp.sigmaA[j], aw + aph + ay, 2e-4 * (aw + aph + ay)) << l << " nm";
            EXPECT_NEAR(mp.sigmaS[j], bw + bp, 2e-3 * (bw + bp)) << l << " nm";
            EXPECT_NEAR(mp.sigmaSComponent[0][j], bw, 2e-3 * bw);
            EXPECT_NEAR(m->sigmaSAt(Vec3(1.f, 1.f, 1.f), ctx, l), bw + bp, 2e-3 * (bw + bp));
            float perComponent[3];
            m->sigmaAComponentsAt(Vec3(1.f, 1.f, 1.f), ctx, l, perComponent);
            EXPECT_NEAR(perComponent[1], aph, 2e-4 * aph);
        }
    }
}

TEST(OceanMedium, MajorantBoundsSigmaTAtRandomPointsAndWavelengths) {
    auto m = oceanMedium(chlorophyllAt);
    Medium::Context ctx(*m);
    Sampler s(5, 0, 0);
    const Bounds3& b = m->majorant().bounds();
    int tight = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        // Wavelengths anywhere in 360–830 nm, not only the visible importance density.
        SampledWavelengths w;
        for (int j = 0; j < kSpectrumSamples; ++j) {
            w.lambda[j] = kLambdaMin + s.get1D() * (kLambdaMax - kLambdaMin);
            w.pdf[j] = 1.f;
        }
        ctx.setWavelengths(w);
        Vec3 p(lerp(s.get1D(), b.lo.x, b.hi.x), lerp(s.get1D(), b.lo.y, b.hi.y),
               lerp(s.get1D(), b.lo.z, b.hi.z));
        MediumPoint mp;
        m->eval(p, ctx, &mp);
        float maj = cellAt(m->majorant(), p);
        float sigmaT = (mp.sigmaA + mp.sigmaS).maxValue();
        ASSERT_GE(maj, sigmaT) << "at " << p.x << " " << p.y << " " << p.z;
        tight += sigmaT > 0.5f * maj;
    }
    // A bound, but not a wild one: most lookups use at least half of it.
    EXPECT_GT(tight, 2000);
}

TEST(OceanMedium, HomogeneousChlorophyllMajorantIsMaxOverWavelength) {
    ShaderDesc s;
    s.name = "chl";
    MediumComponent c;
    makeChlorophyll(&c);
    c.concentration = 5.f;
    s.components = {c};
    Bounds3 box;
    box.expand(Vec3(0.f));
    box.expand(Vec3(1.f));
    Medium m(s, box, Transform(), 1.f);
    // By brute force at 0.1 nm: the majorant bounds max σt and is no looser than the sum of
    // the separate maxima of σa (blue peak, 440 nm) and σs (∝ 1/λ, at 360 nm) it is built from.
    double bestT = 0.0, bestA = 0.0, bestS = 0.0;
    for (float l = kLambdaMin; l <= kLambdaMax; l += 0.1f) {
        double a = ocean::bricaudA()(l) * std::pow(5.0, 1.0 - ocean::bricaudB()(l));
        double sc = 0.30 * std::pow(5.0, 0.62) * 550.0 / l;
        bestT = std::max(bestT, a + sc);
        bestA = std::max(bestA, a);
        bestS = std::max(bestS, sc);
    }
    EXPECT_GE(m.majorant().maxValue(), bestT);
    EXPECT_LT(m.majorant().maxValue(), (bestA + bestS) * 1.01);
}

TEST(OceanMedium, RayOpticalDepthHandlesNonLinearChlorophyll) {
    // The photon estimates' deterministic τ(t, λ) against a fine midpoint sum of σt(x, λ) from
    // Medium::eval (which applies C^(1−B(λ)) exactly) along the same ray.
    auto m = oceanMedium(chlorophyllAt);
    RayOpticalDepth depth({m.get()});
    Ray ray{Vec3(-0.2f, 0.9f, 1.1f), normalize(Vec3(1.f, 0.15f, -0.1f)), kInfinity};
    depth.march(ray, kInfinity);
    ASSERT_FALSE(depth.grey());
    Medium::Context ctx(*m);
    for (float lambda : {412.f, 443.f, 560.f, 675.f, 700.f}) {
        SampledWavelengths w;
        w.lambda.fill(lambda);
        w.pdf.fill(1.f);
        ctx.setWavelengths(w);
        const float t = 2.2f;
        const int n = 20000;
        double tau = 0.0;
        float a, b;
        ASSERT_TRUE(m->objectBounds().intersect(ray.o, ray.d, 0.f, t, &a, &b));
        for (int i = 0; i < n; ++i) {
            MediumPoint mp;
            m->eval(ray.at(a + (b - a) * (i + 0.5f) / n), ctx, &mp);
            tau += (mp.sigmaA[0] + mp.sigmaS[0]) * (b - a) / n;
        }
        EXPECT_NEAR(-std::log(depth.transmittance(t, lambda)), tau, 3e-3 * tau) << lambda;
    }
}

TEST(WaterPhase, NormalisesToOne) {
    WaterPhase p;
    const int n = 200000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += p.eval(-1.f + (i + 0.5f) * 2.f / n);
    EXPECT_NEAR(sum * 2.0 / n * 2.0 * M_PI, 1.0, 1e-5);
    // The published constant 0.06225 is this normalisation, rounded.
    EXPECT_NEAR(WaterPhase::kNorm, 0.06225f, 1e-5f);
}

TEST(WaterPhase, InverseCdfIsExact) {
    // F(μ(u)) = u to 1e-6 over the whole range, including u ≈ 0.5 where μ ≈ 0.
    const double b = WaterPhase::kB;
    for (int i = 0; i <= 1000; ++i) {
        double u = i / 1000.0;
        double mu = WaterPhase::sampleCosTheta(float(u));
        double F = ((mu + 1.0) + b * (mu * mu * mu + 1.0) / 3.0) / (2.0 + 2.0 * b / 3.0);
        ASSERT_NEAR(F, u, 1e-6) << "u = " << u;
    }
}

TEST(WaterPhase, SamplesMatchPdfChiSquare) {
    WaterPhase p;
    const int bins = 40, n = 400000;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    Vec3 wi = normalize(Vec3(0.3f, -0.5f, 0.8f));
    Sampler s(17, 0, 0);
    for (int i = 0; i < n; ++i) {
        float pdf;
        Vec3 wo = p.sample(wi, s.get1D(), s.get1D(), &pdf);
        ASSERT_NEAR(length(wo), 1.f, 1e-4f);
        ASSERT_NEAR(pdf, p.eval(wi, wo), 1e-3f * pdf);
        float mu = clamp(dot(wi, wo), -1.f, 0.999999f);
        observed[int((mu + 1.f) * 0.5f * bins)] += 1;
    }
    for (int k = 0; k < bins; ++k) {
        // ∫ 2π p dμ over the bin, in closed form.
        double lo = -1.0 + 2.0 * k / bins, hi = lo + 2.0 / bins;
        double integral = (hi - lo) + WaterPhase::kB * (hi * hi * hi - lo * lo * lo) / 3.0;
        expected[k] = n * 2.0 * M_PI * WaterPhase::kNorm * integral;
    }
    auto chi = test::chiSquare(observed, expected);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof)) << "dof " << chi.dof;
}
