// Phase functions. Convention: wi is the direction light travels *before* scattering, wo the
// direction it travels *after*; cosθ = dot(wi, wo), so g > 0 means forward scattering.
// Every phase function is normalised over the sphere (∫ p dω = 1, units 1/sr) and is sampled
// exactly, so the sampling weight p/pdf is 1.
#pragma once

#include "core/math.h"
#include "core/sampling.h"

namespace mirage {

// Henyey–Greenstein (1941): p(θ) = (1 − g²) / (4π (1 + g² − 2g cosθ)^{3/2}); mean cosine g.
// g = 0 is isotropic. |g| is clamped to 0.9999 to keep the density finite.
class HGPhase {
public:
    explicit HGPhase(float g = 0.f) : mG(clamp(g, -0.9999f, 0.9999f)) {}
    float g() const { return mG; }

    float eval(float cosTheta) const {
        float denom = 1.f + mG * mG - 2.f * mG * cosTheta;
        return kInv4Pi * (1.f - mG * mG) / (denom * safeSqrt(denom));
    }
    float eval(const Vec3& wi, const Vec3& wo) const { return eval(dot(wi, wo)); }

    // Samples wo given wi by inverting the HG CDF in cosθ; returns wo, *pdf = p(wi, wo).
    Vec3 sample(const Vec3& wi, float u1, float u2, float* pdf) const {
        float cosTheta;
        if (std::abs(mG) < 1e-3f) {
            cosTheta = 1.f - 2.f * u1;
        } else {
            float sq = (1.f - mG * mG) / (1.f - mG + 2.f * mG * u1);
            cosTheta = clamp((1.f + mG * mG - sq * sq) / (2.f * mG), -1.f, 1.f);
        }
        float sinTheta = safeSqrt(1.f - cosTheta * cosTheta);
        float phi = 2.f * kPi * u2;
        Frame f(wi);
        Vec3 wo = f.toWorld(sphericalDirection(sinTheta, cosTheta, phi));
        if (pdf) *pdf = eval(cosTheta);
        return wo;
    }

private:
    float mG;
};

// Molecular scattering by sea water (Morel 1974; the "Rayleigh-like" lobe of Gutierrez et al.
// 2005): p_w(θ) = k (1 + b cos²θ), b = 0.835 (depolarisation ratio 0.09). Normalising
// ∫ p dω = 2πk (2 + 2b/3) = 1 gives k = 3 / (4π (3 + b)) = 0.0622498, published rounded to
// 0.06225. Sampled exactly by inverting its CDF in μ = cosθ, a cubic:
//   F(μ) = [(μ + 1) + b (μ³ + 1)/3] / (2 + 2b/3) = u  ⇔  μ³ + (3/b) μ − 3k'/b = 0,
// k' = u (2 + 2b/3) − 1 − b/3. With p = 3/b > 0 the cubic has one real root (Cardano), taken
// in double precision where the two cube roots nearly cancel (μ ≈ 0).
class WaterPhase {
public:
    static constexpr float kB = 0.835f;
    static constexpr float kNorm = 3.f / (4.f * kPi * (3.f + kB));

    float eval(float cosTheta) const { return kNorm * (1.f + kB * cosTheta * cosTheta); }
    float eval(const Vec3& wi, const Vec3& wo) const { return eval(dot(wi, wo)); }

    static float sampleCosTheta(float u) {
        const double b = kB;
        double k = double(u) * (2.0 + 2.0 * b / 3.0) - 1.0 - b / 3.0;
        double p = 3.0 / b, q = -3.0 * k / b;
        double disc = std::sqrt(q * q / 4.0 + p * p * p / 27.0);
        double mu = std::cbrt(-q / 2.0 + disc) + std::cbrt(-q / 2.0 - disc);
        return clamp(float(mu), -1.f, 1.f);
    }

    Vec3 sample(const Vec3& wi, float u1, float u2, float* pdf) const {
        float cosTheta = sampleCosTheta(u1);
        float sinTheta = safeSqrt(1.f - cosTheta * cosTheta);
        float phi = 2.f * kPi * u2;
        Frame f(wi);
        Vec3 wo = f.toWorld(sphericalDirection(sinTheta, cosTheta, phi));
        if (pdf) *pdf = eval(cosTheta);
        return wo;
    }
};

// The lobe of one medium component: Henyey–Greenstein or the sea-water lobe.
enum class PhaseKind { HenyeyGreenstein, Water };

class ComponentPhase {
public:
    explicit ComponentPhase(PhaseKind kind = PhaseKind::HenyeyGreenstein, float g = 0.f)
        : mKind(kind), mHG(g) {}
    float eval(float cosTheta) const {
        return mKind == PhaseKind::Water ? mWater.eval(cosTheta) : mHG.eval(cosTheta);
    }
    Vec3 sample(const Vec3& wi, float u1, float u2, float* pdf) const {
        return mKind == PhaseKind::Water ? mWater.sample(wi, u1, u2, pdf)
                                         : mHG.sample(wi, u1, u2, pdf);
    }
    PhaseKind kind() const { return mKind; }
    float g() const { return mKind == PhaseKind::Water ? 0.f : mHG.g(); }
    bool operator==(const ComponentPhase& o) const { return mKind == o.mKind && g() == o.g(); }

private:
    PhaseKind mKind;
    HGPhase mHG;
    WaterPhase mWater;
};

}  // namespace mirage
