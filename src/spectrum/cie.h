// CIE 1931 2° colour-matching functions, embedded at 5 nm from the CIE 2018 open data set
// (DOI 10.25039/CIE.DS.xvudnb9b), refined to 1 nm by Sprague interpolation at compile time
// (CIE 167:2005) and interpolated linearly between those; tested against the full 1 nm table in
// ../shared/data/spectra (cie.cpp explains why linear interpolation of 5 nm is not enough).
#pragma once

#include "core/math.h"
#include "core/spectral.h"

namespace mirage {

// ∫ ȳ(λ) dλ over 360–830 nm at 1 nm steps (CIE): the normalisation of Y so that a constant
// spectrum of radiance 1 has Y = 1.
constexpr float kCieYIntegral = 106.856895f;

Vec3 cieXyz(float lambdaNm);  // (x̄, ȳ, z̄) at lambda; 0 outside [360, 830]

// Monte Carlo XYZ of one spectral sample: Σ_i L(λ_i) cmf(λ_i) / pdf(λ_i) / (N · ∫ȳ).
Vec3 spectrumToXyz(const SampledSpectrum& L, const SampledWavelengths& w);

// spectrumToXyz for several spectra at the same wavelengths (a sample's beauty and its render
// passes): the colour-matching values looked up once, the same arithmetic, the same bits.
class SampleXyz {
public:
    explicit SampleXyz(const SampledWavelengths& w);
    Vec3 operator()(const SampledSpectrum& L) const;

private:
    Vec3 mCmf[kSpectrumSamples];
    float mPdf[kSpectrumSamples];
};

}  // namespace mirage
