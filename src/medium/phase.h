// Phase functions. Convention: wi is the direction light travels *before* scattering, wo the
// direction it travels *after*; cosθ = dot(wi, wo), so g > 0 means forward scattering.
// Every phase function is normalised over the sphere (∫ p dω = 1, units 1/sr) and is sampled
// exactly, so the sampling weight p/pdf is 1.
#pragma once

#include "core/math.h"
#include "core/sampling.h"

namespace mirage {

// The direction at angle θ (cosTheta) from wi, at azimuth 2π·u about it: every lobe below is
// symmetric about wi and samples its cosθ alone.
inline Vec3 directionAbout(const Vec3& wi, float cosTheta, float u) {
    return Frame(wi).toWorld(
        sphericalDirection(safeSqrt(1.f - cosTheta * cosTheta), cosTheta, 2.f * kPi * u));
}

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

    // The inverse of the HG CDF in cosθ at u ∈ [0, 1]: with s = (1 − g²)/(1 + g a), a = 2u − 1,
    //     cosθ = (1 + g² − s²) / (2g)
    //          = [a (1 + g²) + (g/2)((a² + 3) + g² (a² − 1))] / (1 + g a)²,
    // the second form expanded so that nothing cancels as g → 0 (the first loses ~ε/g, a
    // visible error below |g| ≈ 1e-3, and divides by zero at g = 0, where the second is a,
    // uniform in cosθ). The second cancels instead near a = −1 when g → 1 (its numerator is
    // −(1 − g)²), where the first is exact: each is used where it is stable. The expanded form
    // takes u ↦ 1 − u (as uniform), so that g = 0 gives the 1 − 2u it always did.
    static float sampleCosTheta(float g, float u) {
        float cosTheta;
        if (std::abs(g) < 0.1f) {
            const float a = 1.f - 2.f * u;
            const float d = 1.f + g * a;
            cosTheta = (a * (1.f + g * g) + 0.5f * g * ((a * a + 3.f) + g * g * (a * a - 1.f))) /
                       (d * d);
        } else {
            const float sq = (1.f - g * g) / (1.f - g + 2.f * g * u);
            cosTheta = (1.f + g * g - sq * sq) / (2.f * g);
        }
        return clamp(cosTheta, -1.f, 1.f);
    }

    // Samples wo given wi by inverting the HG CDF in cosθ; returns wo, *pdf = p(wi, wo).
    Vec3 sample(const Vec3& wi, float u1, float u2, float* pdf) const {
        const float cosTheta = sampleCosTheta(mG, u1);
        if (pdf) *pdf = eval(cosTheta);
        return directionAbout(wi, cosTheta, u2);
    }

private:
    float mG;
};

// The lobe k (1 + b cos²θ): Rayleigh scattering by small particles (b = 1) and its
// depolarised form for sea water (below). Normalising ∫ p dω = 2πk (2 + 2b/3) = 1 gives
// k = 3 / (4π (3 + b)). Sampled exactly by inverting its CDF in μ = cosθ, a cubic:
//   F(μ) = [(μ + 1) + b (μ³ + 1)/3] / (2 + 2b/3) = u  ⇔  μ³ + (3/b) μ − 3k'/b = 0,
// k' = u (2 + 2b/3) − 1 − b/3. With p = 3/b > 0 the cubic has one real root (Cardano), taken
// in double precision where the two cube roots nearly cancel (μ ≈ 0).
inline float cosSquaredNorm(float b) { return 3.f / (4.f * kPi * (3.f + b)); }
inline float sampleCosSquaredLobe(double b, float u) {
    double k = double(u) * (2.0 + 2.0 * b / 3.0) - 1.0 - b / 3.0;
    double p = 3.0 / b, q = -3.0 * k / b;
    double disc = std::sqrt(q * q / 4.0 + p * p * p / 27.0);
    double mu = std::cbrt(-q / 2.0 + disc) + std::cbrt(-q / 2.0 - disc);
    return clamp(float(mu), -1.f, 1.f);
}

// Molecular scattering by sea water (Morel 1974; the "Rayleigh-like" lobe of Gutierrez et al.
// 2005): p_w(θ) = k (1 + b cos²θ), b = 0.835 (depolarisation ratio 0.09), k = 0.0622498,
// published rounded to 0.06225.
class WaterPhase {
public:
    static constexpr float kB = 0.835f;
    static constexpr float kNorm = 3.f / (4.f * kPi * (3.f + kB));

    float eval(float cosTheta) const { return kNorm * (1.f + kB * cosTheta * cosTheta); }
    float eval(const Vec3& wi, const Vec3& wo) const { return eval(dot(wi, wo)); }

    static float sampleCosTheta(float u) { return sampleCosSquaredLobe(kB, u); }

    Vec3 sample(const Vec3& wi, float u1, float u2, float* pdf) const {
        float cosTheta = sampleCosTheta(u1);
        if (pdf) *pdf = eval(cosTheta);
        return directionAbout(wi, cosTheta, u2);
    }
};

// Rayleigh scattering (unpolarised light, particles much smaller than the wavelength):
// p(θ) = 3/(16π) (1 + cos²θ), the lobe above at b = 1; mean cosine 0.
class RayleighPhase {
public:
    static constexpr float kNorm = 3.f / (16.f * kPi);
    float eval(float cosTheta) const { return kNorm * (1.f + cosTheta * cosTheta); }
    static float sampleCosTheta(float u) { return sampleCosSquaredLobe(1.0, u); }
};

// Schlick's approximation of Henyey–Greenstein (Blasi, Le Saëc & Schlick 1993), a rational
// lobe without the 3/2 power: p(θ) = (1 − k²) / (4π (1 − k cosθ)²), normalised for |k| < 1,
// with k = 1.55 g − 0.55 g³ so that its shape follows HG of asymmetry g (its mean cosine is
// close to g, not equal: 0.53 for g = 0.5, −0.76 for g = −0.7). Its CDF inverts in closed form,
//     F(μ) = (1 − k²)/(2k) [1/(1 − kμ) − 1/(1 + k)] = u  ⇔  μ = (a + k) / (1 + k a),
// a = 2u − 1, a form that is exact down to k = 0 (uniform).
class SchlickPhase {
public:
    // 1.55g − 0.55g³ exceeds 1 for g above 0.95 (its maximum is 1.0016 at g = 0.969), where the
    // lobe would not normalise: k is held within ±0.9999, like HG's g.
    explicit SchlickPhase(float g = 0.f)
        : mG(clamp(g, -0.9999f, 0.9999f)),
          mK(clamp(1.55f * mG - 0.55f * mG * mG * mG, -0.9999f, 0.9999f)) {}
    float g() const { return mG; }
    float k() const { return mK; }
    float eval(float cosTheta) const {
        float d = 1.f - mK * cosTheta;
        return kInv4Pi * (1.f - mK * mK) / (d * d);
    }
    float sampleCosTheta(float u) const {
        float a = 2.f * u - 1.f;
        return clamp((a + mK) / (1.f + mK * a), -1.f, 1.f);
    }

private:
    float mG, mK;
};

// The Mie lobes of hazy and murky air (Nishita et al. 1987; as published in Jarosz 2008,
// thesis, chapter 4, and in Gutierrez's thesis, equation 4.24):
//     p(θ) = (1/4π) (1/2 + (c/2) x^n),  x = (1 + cosθ)/2,  (c, n) = (9, 8) hazy, (33, 32) murky,
// normalised over the sphere as published (c = n + 1 makes ∫ (1/2 + (c/2) x^n) dμ = 2), with
// mean cosines c n / ((n + 2)(n + 1 + c)) = 2/5 hazy and 8/17 ≈ 0.47 murky. (The murky
// 1 + 50 x^32 seen elsewhere is not normalised and, renormalised, has a mean cosine of 0.57.)
// Written for any (c, n) as p ∝ 1 + c x^n: ∫ dμ over [−1, 1] is 2 + 2c/(n + 1), so
// p = (1 + c x^n) / (2π (2 + 2c/(n + 1))). Sampled exactly as the mixture it is: the constant,
// with probability 2 / (2 + 2c/(n + 1)), uniform in μ; else the peak, whose density in x ∝ x^n
// inverts to x = u^(1/(n + 1)).
class MiePhase {
public:
    MiePhase(float c, int n) : mC(c), mN(n) {
        const float area = 2.f + 2.f * c / float(n + 1);
        mNorm = 1.f / (2.f * kPi * area);
        mPUniform = 2.f / area;
    }
    static MiePhase hazy() { return MiePhase(9.f, 8); }
    static MiePhase murky() { return MiePhase(33.f, 32); }
    float eval(float cosTheta) const {
        float x = 0.5f * (1.f + cosTheta);
        return mNorm * (1.f + mC * std::pow(std::max(x, 0.f), float(mN)));
    }
    float sampleCosTheta(float u) const {
        if (u < mPUniform) return clamp(2.f * (u / mPUniform) - 1.f, -1.f, 1.f);
        float v = std::min((u - mPUniform) / (1.f - mPUniform), 1.f);
        return clamp(2.f * std::pow(v, 1.f / float(mN + 1)) - 1.f, -1.f, 1.f);
    }

private:
    float mC;
    int mN;
    float mNorm, mPUniform;
};

// The lobe of one medium component. Every kind is normalised and sampled exactly (its pdf is
// its value), so the sampling weight p/pdf is 1:
//  - HenyeyGreenstein (g), Schlick (g), Rayleigh, MieHazy, MieMurky, Water (above);
//  - DoubleHG: w HG(g) + (1 − w) HG(g2), a forward and a back lobe (Kattawar 1975), sampled
//    by choosing a lobe with probability w and 1 − w and reporting the mixture's pdf.
enum class PhaseKind { HenyeyGreenstein, Water, Schlick, Rayleigh, MieHazy, MieMurky, DoubleHG };

class ComponentPhase {
public:
    explicit ComponentPhase(PhaseKind kind = PhaseKind::HenyeyGreenstein, float g = 0.f,
                            float g2 = 0.f, float weight = 1.f)
        : mKind(kind),
          mHG(g),
          mHG2(g2),
          mWeight(kind == PhaseKind::DoubleHG ? clamp(weight, 0.f, 1.f) : 1.f),
          mSchlick(g),
          mMie(kind == PhaseKind::MieMurky ? MiePhase::murky() : MiePhase::hazy()) {}

    float eval(float cosTheta) const {
        switch (mKind) {
            case PhaseKind::Water: return mWater.eval(cosTheta);
            case PhaseKind::Schlick: return mSchlick.eval(cosTheta);
            case PhaseKind::Rayleigh: return mRayleigh.eval(cosTheta);
            case PhaseKind::MieHazy:
            case PhaseKind::MieMurky: return mMie.eval(cosTheta);
            case PhaseKind::DoubleHG:
                return mWeight * mHG.eval(cosTheta) + (1.f - mWeight) * mHG2.eval(cosTheta);
            case PhaseKind::HenyeyGreenstein: break;
        }
        return mHG.eval(cosTheta);
    }
    Vec3 sample(const Vec3& wi, float u1, float u2, float* pdf) const {
        if (mKind == PhaseKind::HenyeyGreenstein) return mHG.sample(wi, u1, u2, pdf);
        if (mKind == PhaseKind::Water) return mWater.sample(wi, u1, u2, pdf);
        const float cosTheta = sampleCosTheta(u1);
        if (pdf) *pdf = eval(cosTheta);
        return directionAbout(wi, cosTheta, u2);
    }
    // cosθ from one uniform number, distributed as eval().
    float sampleCosTheta(float u) const {
        switch (mKind) {
            case PhaseKind::Water: return WaterPhase::sampleCosTheta(u);
            case PhaseKind::Schlick: return mSchlick.sampleCosTheta(u);
            case PhaseKind::Rayleigh: return RayleighPhase::sampleCosTheta(u);
            case PhaseKind::MieHazy:
            case PhaseKind::MieMurky: return mMie.sampleCosTheta(u);
            case PhaseKind::DoubleHG:
                // The lobe by u < w, then u rescaled to [0, 1) within it.
                if (u < mWeight) return HGPhase::sampleCosTheta(mHG.g(), u / mWeight);
                return HGPhase::sampleCosTheta(mHG2.g(),
                                               std::min((u - mWeight) / (1.f - mWeight), 1.f));
            case PhaseKind::HenyeyGreenstein: break;
        }
        return HGPhase::sampleCosTheta(mHG.g(), u);
    }
    PhaseKind kind() const { return mKind; }
    // The asymmetry parameter the lobe was given (HG, Schlick, the first lobe of DoubleHG);
    // 0 for the lobes without one.
    float g() const {
        switch (mKind) {
            case PhaseKind::HenyeyGreenstein:
            case PhaseKind::DoubleHG: return mHG.g();
            case PhaseKind::Schlick: return mSchlick.g();
            default: return 0.f;
        }
    }
    bool operator==(const ComponentPhase& o) const {
        return mKind == o.mKind && g() == o.g() && mHG2.g() == o.mHG2.g() &&
               mWeight == o.mWeight;
    }

private:
    PhaseKind mKind;
    HGPhase mHG, mHG2;
    float mWeight;  // of the first HG lobe (DoubleHG)
    WaterPhase mWater;
    SchlickPhase mSchlick;
    RayleighPhase mRayleigh;
    MiePhase mMie;
};

}  // namespace mirage
