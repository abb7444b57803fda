// Homogeneous media: a box of constant coefficients. Transmittance takes Beer–Lambert's closed
// form (exact, noiseless), also through a transform and next to a heterogeneous medium; delta
// tracking in a grey box meets no null collision and its free flights are exponential.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "test_support.h"
#include "transport/tracking.h"

using namespace mirage;

namespace {

ShaderDesc constantShader(const Spectrum& sigmaA, const Spectrum& sigmaS, float g = 0.f) {
    ShaderDesc s;
    s.name = "fog";
    MediumComponent c;
    c.name = "fog";
    c.sigmaA = sigmaA;
    c.sigmaS = sigmaS;
    c.g = g;
    s.components.push_back(c);
    return s;
}

Bounds3 box(const Vec3& lo, const Vec3& hi) {
    Bounds3 b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

SampledWavelengths wavelengths(float l0, float l1, float l2, float l3) {
    SampledWavelengths w;
    w.lambda = {l0, l1, l2, l3};
    w.pdf.fill(1.f);
    return w;
}

}  // namespace

TEST(HomogeneousMedium, BuildsFromABox) {
    Transform xf = Transform::translate(Vec3d(1.0, 2.0, 3.0));
    Medium m(constantShader(Spectrum(1.f), Spectrum(2.f)), box(Vec3(0.f), Vec3(1.f, 2.f, 4.f)), xf,
             1.5f);
    EXPECT_TRUE(m.homogeneous());
    EXPECT_EQ(m.worldBounds().lo, Vec3(1.f, 2.f, 3.f));
    EXPECT_EQ(m.worldBounds().hi, Vec3(2.f, 4.f, 7.f));
    // One majorant cell holding σt × densityScale.
    EXPECT_EQ(m.majorant().res(0) * m.majorant().res(1) * m.majorant().res(2), 1);
    EXPECT_FLOAT_EQ(m.majorant().maxValue(), 4.5f);
}

TEST(HomogeneousMedium, RejectsGridsEmissionAndEmptyBoxes) {
    ShaderDesc withGrid = constantShader(Spectrum(1.f), Spectrum(1.f));
    withGrid.components[0].grid = "density";
    EXPECT_THROW(Medium(withGrid, box(Vec3(0.f), Vec3(1.f)), Transform(), 1.f), MirageError);
    ShaderDesc emitting = constantShader(Spectrum(1.f), Spectrum(1.f));
    emitting.emission = EmissionSpec{};
    EXPECT_THROW(Medium(emitting, box(Vec3(0.f), Vec3(1.f)), Transform(), 1.f), MirageError);
    EXPECT_THROW(Medium(constantShader(Spectrum(1.f), Spectrum(1.f)), Bounds3(), Transform(), 1.f),
                 MirageError);
}

TEST(HomogeneousMedium, TransmittanceIsBeerLambertExactly) {
    // Spectral σt: σa rises linearly with λ, σs is grey.
    Spectrum sigmaA = Spectrum::fromTable({400.f, 700.f}, {0.5f, 2.0f});
    Medium m(constantShader(sigmaA, Spectrum(1.f)), box(Vec3(0.f), Vec3(2.f, 1.f, 1.f)),
             Transform(), 1.f);
    TrackingContext ctx({&m});
    SampledWavelengths w = wavelengths(400.f, 500.f, 600.f, 700.f);
    ctx.setWavelengths(w);
    Sampler s(1, 0, 0);
    struct Case {
        Vec3 o, d;
        float tMax, inside;  // metres of the ray in the box
    };
    const Vec3 diag = normalize(Vec3(2.f, 1.f, 0.f));
    const Case cases[] = {
        {Vec3(-1.f, 0.5f, 0.5f), Vec3(1, 0, 0), kInfinity, 2.f},   // through, from outside
        {Vec3(0.5f, 0.5f, 0.5f), Vec3(1, 0, 0), kInfinity, 1.5f},  // from inside
        {Vec3(-1.f, 0.5f, 0.5f), Vec3(1, 0, 0), 2.f, 1.f},         // stops inside
        {Vec3(0.f, 0.f, 0.5f), diag, kInfinity, std::sqrt(5.f)},   // corner to corner
        {Vec3(-1.f, 3.f, 0.5f), Vec3(1, 0, 0), kInfinity, 0.f},    // misses
    };
    for (const Case& c : cases) {
        SampledSpectrum T = transmittance(ctx, Ray{c.o, c.d, c.tMax}, c.tMax, s);
        for (int i = 0; i < kSpectrumSamples; ++i) {
            double sigmaT = sigmaA(w.lambda[i]) + 1.0;
            double exact = std::exp(-sigmaT * c.inside);
            EXPECT_NEAR(T[i], exact, 2e-6 + 2e-6 * exact) << "λ " << w.lambda[i];
        }
    }
    EXPECT_EQ(ctx.lookups, 0u);  // closed form: no tentative collision, no noise
}

TEST(HomogeneousMedium, TransmittanceFollowsTheTransform) {
    // A unit cube scaled ×3 along x and rotated 90° about z: in the world it spans 3 m along y.
    Transform xf = Transform::rotate(90.0, Vec3d(0, 0, 1)) * Transform::scale(Vec3d(3, 1, 1));
    const float sigma = 0.7f;
    Medium m(constantShader(Spectrum(0.2f), Spectrum(sigma - 0.2f)), box(Vec3(0.f), Vec3(1.f)), xf,
             1.f);
    TrackingContext ctx({&m});
    ctx.setWavelengths(wavelengths(500.f, 500.f, 500.f, 500.f));
    Sampler s(2, 0, 0);
    SampledSpectrum T =
        transmittance(ctx, Ray{Vec3(-0.5f, -1.f, 0.5f), Vec3(0, 1, 0), kInfinity}, kInfinity, s);
    EXPECT_NEAR(T[0], std::exp(-sigma * 3.0), 1e-6);
}

TEST(HomogeneousMedium, ClosedFormTimesRatioTrackingForMixedMedia) {
    // A homogeneous box and a heterogeneous grid (constant density) overlapping on the ray:
    // T = exp(−σ_hom ℓ_hom) × exp(−σ_grid ℓ_grid); the grid part is estimated.
    Medium fog(constantShader(Spectrum(0.f), Spectrum(1.5f)), box(Vec3(-1.f), Vec3(1.f)),
               Transform(), 1.f);
    ShaderDesc smokeShader = constantShader(Spectrum(0.5f), Spectrum(1.f));
    smokeShader.components[0].grid = "density";
    std::vector<FloatGrid> grids{
        test::makeGrid([](int, int, int) { return 1.f; }, 0, 31, 1.0 / 32)};
    Medium smoke(smokeShader, std::move(grids), Transform(), 1.f, 8);
    TrackingContext ctx({&fog, &smoke});
    ctx.setWavelengths(wavelengths(550.f, 550.f, 550.f, 550.f));
    // Along x at y = z = 0.5 m: 2 m of fog (x ∈ [−1, 1]), the grid's interior from
    // x = 2/32 to 29/32 m (where trilinear interpolation of the constant is exact).
    const float x0 = 2.f / 32, x1 = 29.f / 32;
    double exact = std::exp(-1.5 * (x1 - x0)) * std::exp(-1.5 * (x1 - x0));
    double sum = 0, sum2 = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Sampler s(3, uint64_t(i), 0);
        double T =
            transmittance(ctx, Ray{Vec3(x0, 0.5f, 0.5f), Vec3(1, 0, 0), x1 - x0}, x1 - x0, s)[0];
        sum += T;
        sum2 += T * T;
    }
    double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, exact, 4 * se + 1e-6) << "± " << se;
}

TEST(HomogeneousMedium, DeltaTrackingHasNoNullCollisionsAndExponentialFlights) {
    const float sigmaT = 2.f, L = 1.5f;
    Medium m(constantShader(Spectrum(0.5f), Spectrum(sigmaT - 0.5f)),
             box(Vec3(0.f), Vec3(L, 1.f, 1.f)), Transform(), 1.f);
    TrackingContext ctx({&m});
    ctx.setWavelengths(wavelengths(550.f, 550.f, 550.f, 550.f));
    // E[min(X, L)] = (1 − e^{−σL})/σ for X ~ Exp(σ); P(X > L) = e^{−σL}.
    const int n = 100000;
    double sum = 0, sum2 = 0, escapes = 0;
    for (int i = 0; i < n; ++i) {
        Sampler s(4, uint64_t(i), 0);
        float tFirst = L;
        bool escaped = trackCollisions(ctx, Ray{Vec3(0.f, 0.5f, 0.5f), Vec3(1, 0, 0), kInfinity},
                                       kInfinity, s, [&](const Collision& c) {
                                           EventProbabilities e = eventProbabilities(c);
                                           EXPECT_LT(e.pNull, 1e-6f);
                                           tFirst = c.t;
                                           return Track::Stop;
                                       });
        escapes += escaped;
        sum += tFirst;
        sum2 += double(tFirst) * tFirst;
    }
    double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, (1 - std::exp(-sigmaT * L)) / sigmaT, 4 * se);
    double pEscape = std::exp(-sigmaT * L);
    EXPECT_NEAR(escapes / n, pEscape, 4 * std::sqrt(pEscape * (1 - pEscape) / n));
}
