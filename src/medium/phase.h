// Phase functions. Convention: wi is the direction light travels *before* scattering, wo the
// direction it travels *after*; cosθ = dot(wi, wo), so g > 0 means forward scattering.
// Every phase function is normalised over the sphere (∫ p dω = 1, units 1/sr) and is sampled
// exactly, so the sampling weight p/pdf is 1.
#pragma once

#include "core/math.h"

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
        Vec3 wo = f.toWorld(Vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta));
        if (pdf) *pdf = eval(cosTheta);
        return wo;
    }

private:
    float mG;
};

// Uniform direction on the sphere (isotropic re-emission, light emission).
inline Vec3 sampleUniformSphere(float u1, float u2) {
    float z = 1.f - 2.f * u1;
    float r = safeSqrt(1.f - z * z);
    float phi = 2.f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

}  // namespace mirage
