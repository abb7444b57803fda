// Fluorescence (inelastic scattering), after Gutierrez et al. 2005: a photon of wavelength λi
// absorbed by a fluorescent component is re-emitted with probability Γ (the quantum
// efficiency: photons out per photon absorbed), isotropically, at a wavelength λ drawn from the
// spectral quantum efficiency η(λi → λ). Here η is the emission band of the component, a
// Gaussian of given peak and FWHM (chlorophyll a: 685 nm, 25 nm), independent of λi except for
// the Stokes rule: a molecule cannot emit a photon of more energy (hc/λ) than it absorbed, so
// λ ≥ λi, and η is renormalised over the allowed range. A shader may waive the rule
// (anti_stokes = true: thermally assisted emission, or a deliberate effect).
#pragma once

#include "spectrum/spectrum_sampling.h"

namespace mirage {

// A Gaussian band of unit peak: exp(−(λ − peak)² / (2 s²)), s = FWHM / (2 √(2 ln 2)).
Spectrum gaussianBand(float peakNm, float fwhmNm);

class FluorescenceEmission {
public:
    FluorescenceEmission() = default;
    FluorescenceEmission(float peakNm, float fwhmNm, bool antiStokes);

    // Draws λ (nm) from η(λi → ·) by its inverse CDF. Returns false when no wavelength is
    // allowed (λi beyond the band's red end: nothing to re-emit). *pdf in 1/nm.
    bool sample(float lambdaInNm, float u, float* lambdaOutNm, float* pdf = nullptr) const;
    // Density of λo given λi (1/nm): η(λo) / ∫_{λ ≥ λi} η.
    float pdf(float lambdaInNm, float lambdaOutNm) const;
    bool antiStokes() const { return mAntiStokes; }

private:
    // The part of η's CDF that lies below λi: forbidden (0 when anti-Stokes is allowed).
    double forbiddenMass(float lambdaInNm) const;

    SpectrumSampler mSampler;
    bool mAntiStokes = false;
};

}  // namespace mirage
