#include "geometry/material.h"

#include <utility>

#include "core/sampling.h"

namespace mirage {

Material Material::diffuse(std::string name, Spectrum reflectance, Spectrum emission) {
    Material m;
    m.mName = std::move(name);
    m.mType = MaterialType::Diffuse;
    m.mReflectance = std::move(reflectance);
    m.mEmissive = emission.maxValue() > 0.f;
    m.mEmission = std::move(emission);
    return m;
}

Material Material::mirror(std::string name, Spectrum reflectance) {
    Material m;
    m.mName = std::move(name);
    m.mType = MaterialType::Mirror;
    m.mReflectance = std::move(reflectance);
    return m;
}

Material Material::dielectric(std::string name, float iorA, float cauchyB) {
    Material m;
    m.mName = std::move(name);
    m.mType = MaterialType::Dielectric;
    m.mIorA = iorA;
    m.mCauchyB = cauchyB;
    return m;
}

float Material::ior(float lambdaNm) const {
    float um = lambdaNm * 1e-3f;  // Cauchy's B is tabulated in µm²
    return mIorA + mCauchyB / (um * um);
}

SampledSpectrum Material::emission(const SampledWavelengths& w) const {
    return mEmissive ? mEmission.sample(w) : SampledSpectrum(0.f);
}

float Material::albedo(float lambdaNm) const {
    return mType == MaterialType::Diffuse ? mReflectance(lambdaNm) : 0.f;
}

SampledSpectrum Material::eval(const Vec3& wo, const Vec3& wi, const SampledWavelengths& w) const {
    if (mType != MaterialType::Diffuse || wo.z * wi.z <= 0.f) return SampledSpectrum(0.f);
    return mReflectance.sample(w) * kInvPi;
}

float Material::pdf(const Vec3& wo, const Vec3& wi) const {
    if (mType != MaterialType::Diffuse || wo.z * wi.z <= 0.f) return 0.f;
    return std::abs(wi.z) * kInvPi;
}

float fresnelDielectric(float cosThetaI, float eta) {
    cosThetaI = clamp(cosThetaI, -1.f, 1.f);
    // Arriving from the inside: swap the media.
    if (cosThetaI < 0.f) {
        eta = 1.f / eta;
        cosThetaI = -cosThetaI;
    }
    // Snell: sin θt = sin θi / η; beyond the critical angle all light is reflected.
    float sin2T = (1.f - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2T >= 1.f) return 1.f;
    float cosT = safeSqrt(1.f - sin2T);
    // Fresnel amplitude ratios for light polarised parallel and perpendicular to the plane of
    // incidence; unpolarised light reflects their mean power (Born & Wolf §1.5).
    float rParl = (eta * cosThetaI - cosT) / (eta * cosThetaI + cosT);
    float rPerp = (cosThetaI - eta * cosT) / (cosThetaI + eta * cosT);
    return 0.5f * (rParl * rParl + rPerp * rPerp);
}

bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt) {
    float cosI = dot(n, wi);
    float sin2T = std::max(0.f, 1.f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.f) return false;
    float cosT = safeSqrt(1.f - sin2T);
    *wt = -wi / eta + n * (cosI / eta - cosT);
    return true;
}

bool Material::sample(const Vec3& wo, float uc, float u1, float u2, const SampledWavelengths& w,
                      TransportMode mode, BsdfSample* out) const {
    if (wo.z == 0.f) return false;
    switch (mType) {
    case MaterialType::Diffuse: {
        // Cosine sampling on wo's side: f cos / pdf = (ρ/π) cos / (cos/π) = ρ.
        Vec3 wi = sampleCosineHemisphere(u1, u2);
        if (wo.z < 0.f) wi.z = -wi.z;
        out->wi = wi;
        out->weight = mReflectance.sample(w);
        out->specular = false;
        out->transmitted = false;
        out->dispersed = false;
        return !out->weight.isZero() && wi.z != 0.f;
    }
    case MaterialType::Mirror:
        out->wi = Vec3(-wo.x, -wo.y, wo.z);
        out->weight = mReflectance.sample(w);
        out->specular = true;
        out->transmitted = false;
        out->dispersed = false;
        return !out->weight.isZero();
    case MaterialType::Dielectric: {
        // One direction for the whole path: the hero wavelength's when the index varies.
        float eta = ior(w.lambda[0]);
        out->specular = true;
        out->dispersed = dispersive();
        float R = fresnelDielectric(wo.z, eta);
        if (uc < R) {
            // Reflection with probability R: weight R / R = 1.
            out->wi = Vec3(-wo.x, -wo.y, wo.z);
            out->weight = SampledSpectrum(1.f);
            out->transmitted = false;
            return true;
        }
        // Refraction with probability T = 1 − R: weight T / T, times 1/η'² for radiance,
        // η' = n_t/n_i seen from wo's side.
        Vec3 n(0.f, 0.f, 1.f);
        float etaP = eta;
        if (wo.z < 0.f) {
            etaP = 1.f / eta;
            n = -n;
        }
        Vec3 wi;
        if (!refract(wo, n, etaP, &wi)) return false;  // R = 1 there; reached only by rounding
        out->wi = wi;
        out->weight = SampledSpectrum(mode == TransportMode::Radiance ? 1.f / (etaP * etaP) : 1.f);
        out->transmitted = true;
        return true;
    }
    }
    return false;
}

}  // namespace mirage
