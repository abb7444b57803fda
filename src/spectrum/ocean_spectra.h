// Published optical properties of sea water, embedded so that Mirage needs no data files:
// pure-water absorption and scattering, phytoplankton (chlorophyll) absorption and scattering,
// and coloured dissolved organic matter (CDOM). All coefficients in 1/m, wavelengths in nm,
// chlorophyll concentrations in mg/m³ (the oceanographers' unit, numerically µg/l).
//
// The tables are embedded at a coarser step than published and tested against the full tables
// of ../shared/data/spectra (tests/unit/ocean_spectra_test.cpp); the step was chosen from the
// linear-interpolation error it leaves, stated next to each table in ocean_spectra.cpp.
#pragma once

#include <cmath>

#include "spectrum/spectrum.h"

namespace mirage::ocean {

// One embedded table row: wavelength (nm) and up to two values.
struct TableRow {
    float lambdaNm;
    float a = 0.f, b = 0.f;  // b unused by one-value tables
};
struct EmbeddedTable {
    const TableRow* rows;
    int size;
};

// Pure-water absorption a_w(λ) (1/m): Pope & Fry 1997 on 380–700 nm, other sources outside.
EmbeddedTable waterAbsorptionTable();
// Bricaud et al. 1995 Table 2: a = A(λ) (m²/mg), b = B(λ) (dimensionless), 400–698 nm.
EmbeddedTable bricaudTable();

// The same as spectra (dense 1 nm, linear between rows, held constant beyond the ends).
const Spectrum& waterAbsorption();
const Spectrum& bricaudA();
const Spectrum& bricaudB();

// Phytoplankton absorption a_ph(λ) = A(λ)·Chl^(1−B(λ)) (1/m) for Chl in mg/m³: the
// chlorophyll-specific absorption a*_ph = A·Chl^(−B) of Bricaud et al. 1995 times Chl. Non-linear
// in Chl (pigment packaging flattens a* in rich waters), so it is not a cross-section × grid.
inline float phytoplanktonAbsorption(float A, float B, float chl) {
    return chl > 0.f ? A * std::pow(chl, 1.f - B) : 0.f;
}

// Pure sea-water scattering b_w(λ) = b_w(500)·(λ/500)^−4.32 (1/m), Morel 1974: molecular
// (density-fluctuation) scattering, almost λ^−4 like Rayleigh's, the extra 0.32 from the
// dispersion of the refractive index. b_w(500) = 0.00288 1/m is Morel's value for sea water
// (salinity 35–38 ‰; pure fresh water scatters ≈ 30 % less, 0.00222 1/m).
constexpr float kWaterScattering500 = 0.00288f;  // 1/m
constexpr float kWaterScatteringExponent = 4.32f;
float waterScattering(float lambdaNm);
Spectrum waterScatteringSpectrum();

// Particle (phytoplankton and co-varying detritus) scattering in case-1 waters,
// b_p(λ) = 0.30·Chl^0.62·(550/λ) (1/m): Gordon & Morel 1983, Morel 1988 (b(550) = 0.30·Chl^0.62).
constexpr float kParticleScattering550 = 0.30f;  // 1/m at Chl = 1 mg/m³
constexpr float kParticleScatteringExponent = 0.62f;
inline float particleScatteringPerUnit(float lambdaNm) {  // b_p at Chl^0.62 = 1
    return kParticleScattering550 * 550.f / lambdaNm;
}

// CDOM (yellow substance) absorption a_y(λ) = a_y(440)·exp(−S(λ − 440)) (1/m), Bricaud, Morel &
// Prieur 1981; S = 0.014 1/nm is their mean spectral slope (field values 0.014–0.017).
constexpr float kCdomSlope = 0.014f;  // 1/nm
inline float cdomShape(float lambdaNm, float slope = kCdomSlope) {  // a_y / a_y(440)
    return std::exp(-slope * (lambdaNm - 440.f));
}
Spectrum cdomShapeSpectrum(float slope = kCdomSlope);

}  // namespace mirage::ocean
