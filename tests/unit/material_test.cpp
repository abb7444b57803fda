// Surface materials: Fresnel at normal incidence, total internal reflection, R + T = 1 against
// the transmission coefficients, Snell's law, Cauchy dispersion, χ² of Lambertian sampling.
#include "geometry/material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "core/rng.h"

using namespace mirage;

namespace {

SampledWavelengths grey550() {
    SampledWavelengths w;
    w.lambda.fill(550.f);
    w.pdf.fill(1.f);
    return w;
}

// Fresnel transmittance from the amplitude transmission coefficients t_s, t_p (Born & Wolf
// §1.5.2), an independent route to T: T = (n_t cos θt)/(n_i cos θi) · (t_s² + t_p²)/2.
double fresnelTransmittance(double cosI, double ni, double nt) {
    double sinT = ni / nt * std::sqrt(1.0 - cosI * cosI);
    if (sinT >= 1.0) return 0.0;
    double cosT = std::sqrt(1.0 - sinT * sinT);
    double ts = 2 * ni * cosI / (ni * cosI + nt * cosT);
    double tp = 2 * ni * cosI / (nt * cosI + ni * cosT);
    return nt * cosT / (ni * cosI) * 0.5 * (ts * ts + tp * tp);
}

}  // namespace

TEST(Fresnel, NormalIncidenceIsSquaredIndexRatio) {
    for (float n : {1.33f, 1.5f, 2.4f}) {
        float expected = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
        EXPECT_NEAR(fresnelDielectric(1.f, n), expected, 1e-6f);
        EXPECT_NEAR(fresnelDielectric(-1.f, n), expected, 1e-6f);  // from the inside
    }
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
    const float n = 1.5f;
    const float critical = std::asin(1.f / n);
    for (float dTheta : {0.01f, 0.2f, 0.6f}) {
        float theta = critical + dTheta;
        EXPECT_EQ(fresnelDielectric(-std::cos(theta), n), 1.f);
        Vec3 wo(std::sin(theta), 0.f, -std::cos(theta));  // inside, below the surface
        Vec3 wt;
        EXPECT_FALSE(refract(wo, Vec3(0, 0, -1), 1.f / n, &wt));
        // The material reflects with weight 1 whatever uc.
        Material glass = Material::dielectric("glass", n);
        BsdfSample bs;
        ASSERT_TRUE(glass.sample(wo, 0.999f, 0.f, 0.f, grey550(), TransportMode::Radiance, &bs));
        EXPECT_FALSE(bs.transmitted);
        EXPECT_NEAR(bs.wi.z, wo.z, 1e-6f);  // reflected: stays inside
    }
    // Just inside the critical angle some light still leaves.
    EXPECT_LT(fresnelDielectric(-std::cos(critical - 0.01f), n), 1.f);
}

TEST(Fresnel, ReflectanceAndTransmittanceSumToOne) {
    for (float n : {1.2f, 1.5f, 2.0f})
        for (int i = 0; i <= 20; ++i) {
            double cosI = std::max(1e-3, i / 20.0);
            double R = fresnelDielectric(float(cosI), n);
            EXPECT_NEAR(R + fresnelTransmittance(cosI, 1.0, n), 1.0, 2e-5) << n << " " << cosI;
            // From the inside, below the critical angle.
            double Rin = fresnelDielectric(-float(cosI), n);
            double Tin = fresnelTransmittance(cosI, n, 1.0);
            EXPECT_NEAR(Rin + Tin, 1.0, 2e-5) << "inside " << n << " " << cosI;
        }
}

TEST(Dielectric, SamplingReflectsWithFresnelProbabilityAndObeysSnell) {
    const float n = 1.5f;
    Material glass = Material::dielectric("glass", n);
    Vec3 wo = normalize(Vec3(0.6f, 0.2f, 0.7f));
    const float R = fresnelDielectric(wo.z, n);
    Sampler s(3, 0, 0);
    int reflected = 0;
    const int N = 200000;
    for (int i = 0; i < N; ++i) {
        BsdfSample bs;
        ASSERT_TRUE(glass.sample(wo, s.get1D(), 0.f, 0.f, grey550(), TransportMode::Radiance, &bs));
        if (!bs.transmitted) {
            ++reflected;
            EXPECT_FLOAT_EQ(bs.weight[0], 1.f);
            continue;
        }
        // Snell: sin θi = n sin θt, in the plane of incidence, on the other side.
        float sinI = std::sqrt(1 - wo.z * wo.z), sinT = std::sqrt(1 - bs.wi.z * bs.wi.z);
        EXPECT_NEAR(sinI, n * sinT, 1e-5f);
        EXPECT_LT(bs.wi.z, 0.f);
        EXPECT_NEAR(bs.wi.x * wo.y - bs.wi.y * wo.x, 0.f, 1e-6f);
        EXPECT_NEAR(bs.weight[0], 1.f / (n * n), 1e-6f);  // radiance compression
        BsdfSample imp;
        glass.sample(wo, 0.999f, 0.f, 0.f, grey550(), TransportMode::Importance, &imp);
        EXPECT_FLOAT_EQ(imp.weight[0], 1.f);
    }
    double p = double(reflected) / N, se = std::sqrt(R * (1 - R) / N);
    EXPECT_NEAR(p, R, 4 * se);
}

TEST(Dielectric, CauchyDispersionBendsBlueMoreAndKeepsTheHeroOnly) {
    Material flint = Material::dielectric("flint", 1.6f, 0.01f);
    EXPECT_NEAR(flint.ior(500.f), 1.6f + 0.01f / 0.25f, 1e-6f);
    EXPECT_GT(flint.ior(420.f), flint.ior(680.f));
    EXPECT_TRUE(flint.dispersive());
    EXPECT_FALSE(Material::dielectric("glass", 1.5f).dispersive());
    Vec3 wo = normalize(Vec3(0.7f, 0.f, 0.7f));
    auto refracted = [&](float lambda) {
        SampledWavelengths w;
        w.lambda.fill(lambda);
        w.pdf.fill(1.f);
        BsdfSample bs;
        EXPECT_TRUE(flint.sample(wo, 0.999f, 0.f, 0.f, w, TransportMode::Importance, &bs));
        EXPECT_TRUE(bs.dispersed);
        return bs.wi;
    };
    // Blue is bent closer to the normal (−z) than red.
    EXPECT_LT(refracted(420.f).z, refracted(680.f).z);
}

TEST(Lambertian, CosineSamplingMatchesPdfChiSquare) {
    Material m = Material::diffuse("white", Spectrum(0.7f));
    const int binsTheta = 10, binsPhi = 8, N = 200000;
    std::vector<double> observed(binsTheta * binsPhi, 0.0), expected(binsTheta * binsPhi, 0.0);
    Vec3 wo = normalize(Vec3(0.2f, -0.3f, 0.9f));
    Sampler s(11, 0, 0);
    for (int i = 0; i < N; ++i) {
        BsdfSample bs;
        ASSERT_TRUE(m.sample(wo, s.get1D(), s.get1D(), s.get1D(), grey550(),
                             TransportMode::Radiance, &bs));
        ASSERT_NEAR(bs.weight[0], 0.7f, 1e-6f);  // f cos / pdf = ρ
        ASSERT_NEAR(m.pdf(wo, bs.wi), bs.wi.z * kInvPi, 1e-5f);
        float cosT = clamp(bs.wi.z, 0.f, 0.999999f);
        float phi = std::atan2(bs.wi.y, bs.wi.x) + kPi;
        int it = int(cosT * cosT * binsTheta);  // cos² is uniform under cosine sampling
        int ip = std::min(binsPhi - 1, int(phi / (2 * kPi) * binsPhi));
        observed[size_t(it * binsPhi + ip)] += 1;
    }
    // Under p = cos θ/π the cell [cos²a, cos²b] × [φa, φb] has probability Δ(cos²)/1 · Δφ/2π.
    for (auto& e : expected) e = double(N) / (binsTheta * binsPhi);
    test::ChiSquare c = test::chiSquare(observed, expected);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof)) << c.statistic << " dof " << c.dof;
    // Two-sided: a viewer below samples below.
    BsdfSample bs;
    m.sample(Vec3(0, 0, -1), 0.5f, 0.3f, 0.6f, grey550(), TransportMode::Radiance, &bs);
    EXPECT_LT(bs.wi.z, 0.f);
    EXPECT_NEAR(m.eval(wo, Vec3(0, 0, 1), grey550())[0], 0.7f * kInvPi, 1e-7f);
    EXPECT_EQ(m.eval(wo, Vec3(0, 0, -1), grey550())[0], 0.f);
}

TEST(Mirror, ReflectsAboutTheNormal) {
    Material m = Material::mirror("mirror", Spectrum(0.9f));
    Vec3 wo = normalize(Vec3(0.3f, 0.4f, 0.5f));
    BsdfSample bs;
    ASSERT_TRUE(m.sample(wo, 0.f, 0.f, 0.f, grey550(), TransportMode::Radiance, &bs));
    EXPECT_TRUE(bs.specular);
    EXPECT_NEAR(bs.wi.x, -wo.x, 1e-7f);
    EXPECT_NEAR(bs.wi.y, -wo.y, 1e-7f);
    EXPECT_NEAR(bs.wi.z, wo.z, 1e-7f);
    EXPECT_FLOAT_EQ(bs.weight[0], 0.9f);
}
