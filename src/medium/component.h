// What a component kind (ComponentKind, shader.h) means for a medium: how its coefficients follow
// its concentration C (= concentration × density scale × grid value), an upper bound of them for
// the majorant, and whether they are linear in C. The medium, the photon emitter and the ray
// optical depth ask a component these questions and never branch on its kind, so a new law of
// concentration is one class in component.cpp (plus its name in the shader loader).
//
// Two laws exist:
//  - linear (linear, water, cdom): σa = C · σa(λ), σs = C · σs(λ), the component's spectra being
//    cross-sections per unit concentration. A consumer may then integrate or bound C alone and
//    multiply by σ(λ) afterwards (linear() is true).
//  - power law (chlorophyll): σa = A(λ) · C^e(λ), σs = b(λ) · C^s (Bricaud et al. 1995; Gordon &
//    Morel 1983), the spectra being A and b and the exponents sigmaAExponent, sigmaSExponent.
#pragma once

#include <memory>
#include <vector>

#include "core/spectral.h"
#include "medium/shader.h"
#include "volume/grid.h"
#include "volume/majorant.h"

namespace mirage {

// A component's coefficients at the wavelengths of one path, set once per path
// (Medium::Context::setWavelengths) so that a lookup only combines them with a grid value.
struct PathCoefficients {
    // Linear: σa, σs per unit grid value (concentration × density scale folded in). Power law:
    // A(λ), b(λ) and e(λ), with C = scale × grid value.
    SampledSpectrum sigmaA, sigmaS, exponentA;
    float scale = 1.f;
};

// The integrals I_m = ∫ C^p_m ds along a ray (the powers p_m of ComponentModel::depthPowers),
// interpolated linearly between two nodes of their tabulation: a, b point at the component's
// first integral at the nodes before and after, f ∈ [0, 1] is the position between them.
struct DepthIntegrals {
    const float* a;
    const float* b;
    float f;
    float operator[](int m) const { return a[m] + f * (b[m] - a[m]); }
};

class ComponentModel {
public:
    // The law of c's kind, holding what it needs of c (which may then go away).
    static std::shared_ptr<const ComponentModel> make(const MediumComponent& c);
    virtual ~ComponentModel() = default;

    // σ = C · σ(λ) (see above).
    bool linear() const { return mLinear; }
    // Linear with σa and σs independent of λ: the medium's grey path holds one number per
    // component (Medium::greyCoefficients).
    virtual bool grey() const = 0;

    // σa, σs (1/m) at concentration C for one wavelength.
    virtual float sigmaA(float C, float lambdaNm) const = 0;
    virtual float sigmaS(float C, float lambdaNm) const = 0;
    // σa at concentration C at every whole nanometre 360, 361, …, 830 (Spectrum::kDenseSamples
    // values): the absorption spectrum there, for integrals over λ.
    virtual void sigmaADense(float C, float* out) const = 0;

    // An upper bound of σt = σa + σs (1/m) over every wavelength and every concentration in
    // [0, C], in double so that a huge C is compared before it can overflow float.
    virtual double sigmaTBound(double C) const = 0;
    // Adds to every cell of a majorant the bound at C = k × (the grid's largest value there),
    // or at C = k everywhere for a component without a grid.
    virtual void addToMajorant(MajorantGrid* majorant, const FloatGrid* grid, float k) const = 0;

    // The coefficients at a path's wavelengths for k = concentration × density scale.
    virtual void sampleWavelengths(const SampledWavelengths& w, float k,
                                   PathCoefficients* out) const = 0;
    // At grid value v: adds σa to *sigmaA and writes σs to *sigmaS. The linear law, which every
    // lookup of smoke and fog takes, is inlined here; the others are a virtual call.
    void evalPath(const PathCoefficients& pc, float v, SampledSpectrum* sigmaA,
                  SampledSpectrum* sigmaS) const {
        if (mLinear)
            evalLinear(pc, v, sigmaA, sigmaS);
        else
            evalLaw(pc, v, sigmaA, sigmaS);
    }

    // Optical depth at any wavelength from integrals along the ray: σt(C, λ) is written as
    // Σ_m w_m(λ) C^p_m, and the ray integrates each C^p_m once (transport/ray_optical_depth.h).
    virtual std::vector<float> depthPowers() const = 0;
    // τ(λ) = Σ_m w_m(λ) I_m.
    virtual float opticalDepth(float lambdaNm, const DepthIntegrals& integrals) const = 0;

protected:
    explicit ComponentModel(bool linear) : mLinear(linear) {}
    static void evalLinear(const PathCoefficients& pc, float v, SampledSpectrum* sigmaA,
                           SampledSpectrum* sigmaS) {
        *sigmaA += pc.sigmaA * v;
        *sigmaS = pc.sigmaS * v;
    }
    // evalPath out of line.
    virtual void evalLaw(const PathCoefficients& pc, float v, SampledSpectrum* sigmaA,
                         SampledSpectrum* sigmaS) const = 0;

private:
    bool mLinear;
};

}  // namespace mirage
