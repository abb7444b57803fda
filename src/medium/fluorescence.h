// Fluorescence (inelastic scattering), after Gutierrez et al. 2005: a photon of wavelength λi
// absorbed by a fluorescent component is re-emitted with probability Γ (the quantum
// efficiency: photons out per photon absorbed), isotropically, at a wavelength λ drawn from the
// spectral quantum efficiency η(λi → λ). η is either the emission band of the component, a
// Gaussian of given peak and FWHM (chlorophyll a: 685 nm, 25 nm) independent of λi, or an
// excitation–emission matrix (EEM): emission spectra tabulated at excitation wavelengths, each
// row's shape normalised to unit area (Γ and the component's σa say how much is re-emitted),
// and η(λi → ·) the linear blend of the two rows about λi (the nearest row outside the table).
// Either obeys the Stokes rule: a molecule cannot emit a photon of more energy (hc/λ) than it
// absorbed, so λ ≥ λi, and η is renormalised over the allowed range. A shader may waive the
// rule (anti_stokes = true: thermally assisted emission, or a deliberate effect).
#pragma once

#include <vector>

#include "spectrum/spectrum_sampling.h"

namespace mirage {

// A Gaussian band of unit peak: exp(−(λ − peak)² / (2 s²)), s = FWHM / (2 √(2 ln 2)).
Spectrum gaussianBand(float peakNm, float fwhmNm);

// η tabulated: one emission spectrum per excitation wavelength (strictly increasing, nm). Each
// row must have energy in 360–830 nm (SpectrumSampler throws otherwise).
struct EmissionMatrix {
    std::vector<float> excitationNm;
    std::vector<Spectrum> rows;
};

class FluorescenceEmission {
public:
    FluorescenceEmission() = default;
    FluorescenceEmission(float peakNm, float fwhmNm, bool antiStokes);
    FluorescenceEmission(const EmissionMatrix& matrix, bool antiStokes);

    // Draws λ (nm) from η(λi → ·) by its inverse CDF. Returns false when no wavelength is
    // allowed (λi beyond the band's red end: nothing to re-emit). *pdf in 1/nm.
    bool sample(float lambdaInNm, float u, float* lambdaOutNm, float* pdf = nullptr) const;
    // Density of λo given λi (1/nm): η(λo) / ∫_{λ ≥ λi} η.
    float pdf(float lambdaInNm, float lambdaOutNm) const;
    bool antiStokes() const { return mAntiStokes; }

private:
    // The rows η(λi → ·) blends and their weights (the second weight 0 for a single row).
    struct RowBlend {
        int row[2] = {0, 0};
        float weight[2] = {1.f, 0.f};
    };
    RowBlend blendAt(float lambdaInNm) const;
    // The part of a row's CDF below λi: forbidden (0 when anti-Stokes is allowed).
    double forbiddenMass(int row, float lambdaInNm) const;
    double allowedMass(int row, float lambdaInNm) const {
        return 1.0 - forbiddenMass(row, lambdaInNm);
    }
    // Σ weight·(allowed mass): what the blend renormalises by.
    double allowedTotal(const RowBlend& b, float lambdaInNm) const;

    std::vector<float> mExcitationNm;    // one per row; empty for a band
    std::vector<SpectrumSampler> mRows;  // each row's normalised density
    bool mAntiStokes = false;
};

}  // namespace mirage
