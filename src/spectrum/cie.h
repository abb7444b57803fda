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
// passes): the colour-matching values and the pdf's weights computed once, the same bits for
// every spectrum.
class SampleXyz {
public:
    explicit SampleXyz(const SampledWavelengths& w);
    // Inline: the film calls it for the beauty and each of its passes, every sample.
    Vec3 operator()(const SampledSpectrum& L) const {
        // Most of a sample's render passes hold nothing (its light is direct or indirect, one
        // group's or another's).
        if (L.isZero()) return Vec3(0.f);
        Vec3 sum(0.f);
        for (int i = 0; i < kSpectrumSamples; ++i) sum += mWeight[i] * L[i];
        return sum;
    }

private:
    Vec3 mWeight[kSpectrumSamples];  // cmf(λ_i) / (pdf(λ_i) · N · ∫ȳ); 0 where pdf = 0
};

}  // namespace mirage
