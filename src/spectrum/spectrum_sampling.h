// Wavelength sampling from a spectrum: λ drawn with density p(λ) = S(λ) / ∫ S dλ over
// [360, 830] nm by inverting the CDF exactly. Photons are monochromatic (photon/photon.h), so a
// light draws each photon's wavelength from its normalised spectral power distribution, and the
// photon's power stays Φ/N whatever the colour (the S(λ) of the flux and the pdf cancel).
#pragma once

#include <vector>

#include "spectrum/spectrum.h"

namespace mirage {

class SpectrumSampler {
public:
    SpectrumSampler() = default;  // invalid until built from a spectrum
    // Throws MirageError when S has no energy in [360, 830] nm. Negative values (none should
    // reach a light) count as 0: a density cannot be negative.
    explicit SpectrumSampler(const Spectrum& s);

    bool valid() const { return mIntegral > 0.0; }
    // λ (nm) for u in [0, 1); *pdf = p(λ) in 1/nm when pdf is not null.
    float sample(float u, float* pdf = nullptr) const;
    float pdf(float lambdaNm) const;
    // ∫ S from 360 nm to λ, divided by ∫ S: the CDF of the sampled density (0 below 360 nm,
    // 1 above 830 nm). sample(cdf(λ)) = λ.
    double cdf(float lambdaNm) const;
    // ∫ S dλ over [360, 830] nm (units of S × nm).
    double integral() const { return mIntegral; }

private:
    // S is linear between whole nanometres (Spectrum stores it densely at 1 nm; a constant is
    // linear too), so the CDF is piecewise quadratic and inverts in closed form per interval.
    std::vector<float> mValue;  // S at 360, 361, …, 830 nm, clamped to ≥ 0
    std::vector<double> mCdf;   // ∫ S from 360 nm to each of those wavelengths (unnormalised)
    double mIntegral = 0.0;
};

// One-off form of SpectrumSampler(s).sample(u, pdf): builds the CDF (471 entries) at each call,
// so code that samples a spectrum repeatedly should keep a SpectrumSampler instead.
float sampleWavelength(const Spectrum& s, float u, float* pdf);

}  // namespace mirage
