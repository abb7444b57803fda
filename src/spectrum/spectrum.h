// Spectra: functions of wavelength (nm) that the renderer samples at a path's 4 wavelengths.
// Every non-constant spectrum is stored densely at 1 nm over [360, 830] nm and interpolated
// linearly, so evaluation costs the same whatever its origin (table, blackbody, RGB).
#pragma once

#include <string>
#include <vector>

#include "core/matrix.h"
#include "core/spectral.h"

namespace mirage {

class Spectrum {
public:
    Spectrum() = default;                        // constant 0
    explicit Spectrum(float c) : mConstant(c) {}  // wavelength-independent
    // Piecewise-linear through (lambda_nm[i], value[i]); held constant beyond the ends.
    static Spectrum fromTable(const std::vector<float>& lambdaNm, const std::vector<float>& value);
    // The dense form directly: kDenseSamples values at 360, 361, …, 830 nm.
    static Spectrum fromDense(std::vector<float> values1nm);
    static constexpr int kDenseSamples = 471;

    bool isConstant() const { return mTable.empty(); }
    float constantValue() const { return mConstant; }
    float operator()(float lambdaNm) const;
    SampledSpectrum sample(const SampledWavelengths& w) const;
    float maxValue() const;
    Spectrum scaled(float s) const;

private:
    float mConstant = 0.f;
    std::vector<float> mTable;  // kDenseSamples values, 360..830 nm at 1 nm, when not constant
};

// Planck's law: spectral radiance of a blackbody, W·m⁻²·sr⁻¹·m⁻¹ (per metre of wavelength),
// at wavelength lambdaNm (nm) and temperature T (K). 0 for T <= 0.
double planck(double lambdaNm, double temperatureK);
// Blackbody spectrum normalised to peak 1 over the visible range (a colour, not a power).
Spectrum blackbodyNormalized(float temperatureK);

// RGB → spectrum. Two kinds, because they answer different questions:
//  - reflectance-like values (albedo, σ tints): a smooth partition-of-unity basis
//    B_b + B_g + B_r = 1, so (a,a,a) ↦ the constant a and values in [0,1] stay in [0,1];
//  - illuminants: the same basis with coefficients solved so that the spectrum's XYZ, taken
//    to the working space by `xyzToWorking`, is exactly the given RGB (negative lobes of very
//    saturated colours are clamped to 0).
Spectrum rgbReflectanceSpectrum(const Vec3& rgb);
Spectrum rgbIlluminantSpectrum(const Vec3& rgb, const Mat3& xyzToWorking);
// The pieces of rgbIlluminantSpectrum, for an image of many colours (the dome light's map):
// the matrix taking working-space RGB to the coefficients (c_r, c_g, c_b) of the three basis
// windows (clamp them at 0 before use), and the windows B_r, B_g, B_b as spectra (k = 0, 1, 2).
Mat3 rgbIlluminantCoefficients(const Mat3& xyzToWorking);
Spectrum rgbBasisSpectrum(int k);

// CIE XYZ of a whole spectrum: Σ S(λ) cmf(λ) Δλ / ∫ȳ over 360–830 nm at Δλ = 1 nm, so a constant
// spectrum 1 has Y ≈ 1 (the same normalisation as the per-sample `spectrumToXyz` in cie.h, whose
// expectation this is). rgbIlluminantSpectrum is exact with respect to this sum.
Vec3d spectrumToXyz(const Spectrum& s);

}  // namespace mirage
