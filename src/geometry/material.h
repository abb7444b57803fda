// Surface materials: Lambertian (optionally an area emitter), mirror and dielectric (glass),
// each with sample / eval / pdf in a local shading frame whose normal is +z.
//
// Conventions (pbrt-v4, "BSDFs"): wo points from the surface towards the viewer (or, for a
// photon, back along where it came from), wi is the sampled direction the path continues
// along; both are unit vectors in the local frame. eval returns f(wo, wi) without the cosine;
// a sample's weight is f |cos θi| / pdf per wavelength. For the specular materials f and pdf
// hold Dirac deltas, so eval/pdf return 0 and only sample() is meaningful.
//
// Dielectric (Fresnel equations for unpolarised light, Snell's law, total internal
// reflection): the normal points to the outside (index 1), the inside has index n(λ):
//     n(λ) = A + B / λ²,  λ in µm  (Cauchy; B = 0 for a constant index).
// Reflection is chosen with probability F (the exact Fresnel reflectance), refraction with
// 1 − F, so a sample's weight is 1 for reflection and, for radiance (camera paths), 1/η² for
// refraction with η = n_t / n_i: radiance is compressed into the smaller solid angle of the
// denser medium (Veach 1997, §5.2). Importance (photons) carries no such factor.
// Dispersion: with B ≠ 0 the refracted direction depends on λ, and the 4 hero wavelengths of a
// camera path cannot follow one direction. The path then keeps only its hero wavelength λ[0]
// (sample() sets `dispersed`; the caller zeroes the other three and weights the hero by 4, as
// pbrt-v4's SampledWavelengths::TerminateSecondary does). Photons are monochromatic and
// refract at their own wavelength, so a prism splits the photon map's light with no special
// case.
#pragma once

#include <string>

#include "core/math.h"
#include "core/spectral.h"
#include "spectrum/spectrum.h"

namespace mirage {

enum class MaterialType { Diffuse, Mirror, Dielectric };

// Whether a sample carries radiance (camera paths, weight 1/η² at refraction) or importance
// (photons, no factor).
enum class TransportMode { Radiance, Importance };

struct BsdfSample {
    Vec3 wi;                  // local frame
    SampledSpectrum weight;   // f |cos θi| / pdf per wavelength
    bool specular = false;    // a delta lobe: no NEE, no density estimate at this vertex
    bool transmitted = false;
    bool dispersed = false;   // the direction is valid for the hero wavelength only
};

class Material {
public:
    static Material diffuse(std::string name, Spectrum reflectance, Spectrum emission = {});
    static Material mirror(std::string name, Spectrum reflectance = Spectrum(1.f));
    // Index n(λ) = a + b / λ² with λ in µm (b = 0: constant a).
    static Material dielectric(std::string name, float iorA, float cauchyB = 0.f);

    const std::string& name() const { return mName; }
    MaterialType type() const { return mType; }
    bool specular() const { return mType != MaterialType::Diffuse; }
    bool emissive() const { return mEmissive; }
    bool dispersive() const { return mType == MaterialType::Dielectric && mCauchyB != 0.f; }
    float ior(float lambdaNm) const;
    float iorA() const { return mIorA; }
    float cauchyB() const { return mCauchyB; }
    const Spectrum& reflectance() const { return mReflectance; }
    const Spectrum& emissionSpectrum() const { return mEmission; }

    // Radiance a Lambertian emitter sends from either side (W·m⁻²·sr⁻¹·nm⁻¹); 0 otherwise.
    SampledSpectrum emission(const SampledWavelengths& w) const;
    // Diffuse albedo at wavelength λ (the photon pass's Russian roulette); 0 for specular.
    float albedo(float lambdaNm) const;

    // f(wo, wi) (1/sr), without the cosine. Lambertian is two-sided: ρ/π when wo and wi lie
    // on the same side, 0 otherwise.
    SampledSpectrum eval(const Vec3& wo, const Vec3& wi, const SampledWavelengths& w) const;
    float pdf(const Vec3& wo, const Vec3& wi) const;
    // Samples wi for wo with (uc, u1, u2) uniform in [0, 1). Returns false when the path ends
    // (a black material, or a grazing wo).
    bool sample(const Vec3& wo, float uc, float u1, float u2, const SampledWavelengths& w,
                TransportMode mode, BsdfSample* out) const;

private:
    std::string mName;
    MaterialType mType = MaterialType::Diffuse;
    Spectrum mReflectance{1.f};
    Spectrum mEmission;
    bool mEmissive = false;
    float mIorA = 1.5f, mCauchyB = 0.f;
};

// Exact Fresnel reflectance of a smooth dielectric boundary for unpolarised light: the mean of
// the s and p reflectances, cosThetaI measured on the incident side's normal (negative: the
// ray arrives from the inside), eta = n_inside / n_outside. 1 under total internal reflection.
float fresnelDielectric(float cosThetaI, float eta);

// Refraction of wi (pointing away from the surface, on n's side) through the boundary with
// relative index eta = n_t / n_i; false under total internal reflection.
bool refract(const Vec3& wi, const Vec3& n, float eta, Vec3* wt);

}  // namespace mirage
