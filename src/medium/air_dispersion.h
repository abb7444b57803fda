// The dispersion of air: n(λ) − 1 of air at a reference state, and that state's density, so
// that Gladstone–Dale scales it to any density (n − 1 ∝ ρ). Three formulas:
//  - Cauchy: a(1 + b/λ²) at 0 °C, 101325 Pa with Gutierrez et al. 2005's a = 29.79e−5 and weak
//    b = 5.67e−5 µm² (air_index.h: air::kCauchyA, air::kCauchyBum2), the paper's model;
//  - Edlén 1966 (Metrologia 2, 71, eq. 1), standard air (dry, 15 °C, 101325 Pa, 300 ppm CO₂):
//        10⁸ (n − 1) = 8342.13 + 2406030 / (130 − σ²) + 15997 / (38.9 − σ²),
//  - Ciddor 1996 (Applied Optics 35, 1566, eq. 1), standard air (dry, 15 °C, 101325 Pa,
//    450 ppm CO₂):
//        10⁸ (n − 1) = 5792105 / (238.0185 − σ²) + 167917 / (57.362 − σ²),
//    σ the vacuum wavenumber in 1/µm. Both published within a few parts in 10⁸ of measured
//    standard air (Edlén 5e−8, Ciddor 2e−8 to 5e−8); their dispersion from 400 to 700 nm is
//    about 2.5 %, a hundred times the paper's Cauchy b.
#pragma once

namespace mirage {

enum class AirDispersion { Cauchy, Edlen1966, Ciddor1996 };

// The key's spelling in a scene ("cauchy", "edlen", "ciddor").
const char* airDispersionName(AirDispersion kind);

// n − 1 at the formula's reference state and wavelength λ (vacuum, nm).
double referenceRefractivity(AirDispersion kind, double lambdaNm);
// The density of that reference state by the ideal gas (kg/m³).
double referenceDensity(AirDispersion kind);

}  // namespace mirage
