// The refractive index of air: from temperature alone (Stam & Languenou 1996), from pressure and
// temperature by the ideal gas and Gladstone–Dale with Cauchy dispersion (Gutierrez et al. 2005,
// §4), and the US Standard Atmosphere 1976 with user inversion layers as a stratified field
// (mirages: a layer warmer near the ground bends rays up — inferior mirage; a layer warmer
// above cold sea bends them down — superior mirage).
#pragma once

#include <vector>

#include "medium/index_field.h"

namespace mirage {

namespace air {
// Cauchy dispersion of the refractivity at the reference density: n(λ) − 1 = a(1 + b/λ²),
// λ in µm, with the values of Gutierrez et al. 2005: a = 29.79e−5,
// b = 5.67e−5 µm². Note on realism: the textbook Cauchy coefficients for air at 0 °C and
// 101325 Pa are A = 28.79e−5, B = 5.67e−3 µm² (B = 5.67e−11 cm²), and Edlén's 1966 formula (15 °C)
// gives (n−1)(400 nm)/(n−1)(700 nm) = 1.0252, which B = 5.67e−3 µm² reproduces (1.0239) while the
// paper's b = 5.67e−5 µm² gives 1.00024: about a hundredth of the real dispersion. a = 29.79e−5
// is 3.5 % above the textbook 28.79e−5. Kept as the paper gives them; air_index_test.cpp
// measures both.
constexpr double kCauchyA = 29.79e-5;
constexpr double kCauchyBum2 = 5.67e-5;
// The reference state of those coefficients: 0 °C, 101325 Pa.
constexpr double kRefTemperature = 273.15;  // K
constexpr double kRefPressure = 101325.0;   // Pa
// US Standard Atmosphere 1976 constants (../shared/data/README.md).
constexpr double kGasConstant = 8.31432;    // R*, J/(mol·K)
constexpr double kMolarMass = 0.0289644;    // M0, kg/mol
constexpr double kG0 = 9.80665;             // m/s²
constexpr double kEarthRadius = 6356766.0;  // r0 of the 1976 standard, m
// Stam & Languenou's temperature law n = 1 + (T_p/T)(n0 − 1): the reference T_p = 15 °C and n0
// of standard air there at 550 nm, (n0 − 1) = 2.7782e−4 (Edlén 1966, 101325 Pa). It is
// Gladstone–Dale at constant pressure: n − 1 ∝ ρ ∝ 1/T.
constexpr double kStamTp = 288.15;          // K
constexpr double kStamN0 = 1.00027782;
}  // namespace air

// Ideal-gas density ρ = P M / (R T), kg/m³ (P in Pa, T in K).
double airDensity(double pressurePa, double temperatureK);
// n − 1 at the reference density: a(1 + b/λ²).
double airRefractivity(double lambdaNm, double a = air::kCauchyA, double bUm2 = air::kCauchyBum2);
// Gladstone–Dale: n = 1 + (ρ/ρ_ref)(n(λ) − 1) with ρ_ref the density at 0 °C, 101325 Pa.
double airIndex(double pressurePa, double temperatureK, double lambdaNm);
// Stam & Languenou: n = 1 + (T_p/T)(n0 − 1).
inline double temperatureIndex(double temperatureK, double tp = air::kStamTp,
                               double n0 = air::kStamN0) {
    return 1.0 + (tp / temperatureK) * (n0 - 1.0);
}

// US Standard Atmosphere 1976 below 84.852 km geopotential (extrapolated beyond with the top
// layer's lapse rate): temperature, pressure, density and dT/dH at geopotential height H (m).
struct AtmosphereSample {
    double temperature, pressure, density, dTdH;
};
AtmosphereSample usStandardAtmosphere1976(double geopotentialHeight);
// H = r0 z / (r0 + z) for geometric height z.
inline double geopotentialHeight(double z) { return air::kEarthRadius * z / (air::kEarthRadius + z); }

// A layer warmer (deltaT > 0) or colder than the standard atmosphere between base and top
// (geometric heights, m), each edge blended over `blend` metres by the C² step
// 6t⁵ − 15t⁴ + 10t³, so that ∇n stays continuous (C¹) across it.
struct InversionLayer {
    double base = 0, top = 1, deltaT = 0, blend = 1;
};

struct AtmosphereSettings {
    std::vector<InversionLayer> inversions;
    double groundHeight = 0;  // scene y of sea level (y − groundHeight = geometric height)
};

// The stratified field n(y): T(z) = T_1976(z) + Σ ΔT_i·window_i(z), P(z) = P_1976(z), then
// ρ = PM/(RT) and Gladstone–Dale + Cauchy. Layers change temperature at the standard pressure:
// a thin layer's own hydrostatic change of pressure is ΔT/T × thickness / scale height
// (~1e−4 of P for 30 K over 20 m), which this neglects. ∇n = (0, dn/dy, 0).
class AtmosphereIndexField final : public IndexField {
public:
    explicit AtmosphereIndexField(AtmosphereSettings settings);

    void eval(const Vec3d& x, double lambdaNm, double* n, Vec3d* gradient) const override;
    double gradientBound(const Vec3d& lo, const Vec3d& hi) const override;

    // Temperature (K) and its height derivative at geometric height z: layers included.
    void temperature(double z, double* T, double* dTdz) const;

private:
    // T and dT/dz at z from the 1976 sample there and dH/dz: the layers added.
    void addLayers(double z, const AtmosphereSample& std1976, double dHdz, double* T,
                   double* dTdz) const;
    AtmosphereSettings mSettings;
};

}  // namespace mirage
