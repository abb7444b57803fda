// The refractive index of air: from temperature alone (Stam & Languenou 1996), from pressure and
// temperature by the ideal gas and Gladstone–Dale with Cauchy dispersion (Gutierrez et al. 2005,
// §4) or a published formula (air_dispersion.h), and the US Standard Atmosphere 1976 with user
// inversion layers as a stratified field (mirages: a layer warmer near the ground bends rays
// up — inferior mirage; a layer warmer above cold sea bends them down — superior mirage), on
// flat layers or on spherical shells about a round Earth (sunsets: the refraction of the
// horizon, about 35′, is that of rays grazing a curved atmosphere).
#pragma once

#include <vector>

#include "medium/air_dispersion.h"
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
// The round Earth of the paper's sunsets: the mean radius 6371 km (IUGG), under an atmosphere
// shell 40 km deep (above 40 km n − 1 < 1e−6, 0.3 % of its value at sea level).
constexpr double kMeanEarthRadius = 6371000.0;  // m
constexpr double kShellDepth = 40000.0;         // m
// The shell's top fades n − 1 to 0 over its last kilometre (by the C² step below), so that
// ∇n stays finite and a ray leaves the air without a jump of index.
constexpr double kShellFade = 1000.0;  // m
}  // namespace air

// Ideal-gas density ρ = P M / (R T), kg/m³ (P in Pa, T in K).
double airDensity(double pressurePa, double temperatureK);
// n − 1 at the reference density: a(1 + b/λ²).
double airRefractivity(double lambdaNm, double a = air::kCauchyA, double bUm2 = air::kCauchyBum2);
// Gladstone–Dale: n = 1 + (ρ/ρ_ref)(n_ref(λ) − 1) with n_ref and ρ_ref those of the dispersion
// formula's reference state (Cauchy: 0 °C, 101325 Pa).
double airIndex(double pressurePa, double temperatureK, double lambdaNm,
                AirDispersion dispersion = AirDispersion::Cauchy);
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
inline double geopotentialHeight(double z) {
    return air::kEarthRadius * z / (air::kEarthRadius + z);
}

// How a layer's temperature rises at its edges:
//  - Smooth: over `blend` metres by the C² step 6t⁵ − 15t⁴ + 10t³, so that ∇n stays
//    continuous (C¹) across it and vanishes outside it;
//  - Fermi: by the Fermi distribution 1/(1 + e^(−(z − edge)/a)), a = `blend`, with which
//    Gutierrez et al. interpolate the temperature between their layers (a smooth step with
//    tails: 27 % to 73 % of ΔT within ±a of the edge, 12 % to 88 % within ±2a).
enum class LayerEdge { Smooth, Fermi };

// A layer warmer (deltaT > 0) or colder than the standard atmosphere between base and top
// (geometric heights, m), each edge blended by `edge` over `blend` metres.
struct InversionLayer {
    double base = 0, top = 1, deltaT = 0, blend = 1;
    LayerEdge edge = LayerEdge::Smooth;
};

// Flat: the layers are planes y = const. Round: spherical shells about the Earth's centre
// (0, groundHeight − earthRadius, 0), ending at height `shellDepth` (air::kShellFade).
enum class EarthShape { Flat, Round };

struct AtmosphereSettings {
    std::vector<InversionLayer> inversions;
    double groundHeight = 0;  // scene y of sea level (y − groundHeight = geometric height)
    EarthShape earth = EarthShape::Flat;
    double earthRadius = air::kMeanEarthRadius;  // m, Round only
    double shellDepth = air::kShellDepth;        // m, Round only
    AirDispersion dispersion = AirDispersion::Cauchy;
};

// The stratified field n(z) of height z: T(z) = T_1976(z) + Σ ΔT_i·window_i(z),
// P(z) = P_1976(z), then ρ = PM/(RT) and Gladstone–Dale with the chosen dispersion. Layers change
// temperature at the standard pressure: a thin layer's own hydrostatic change of pressure is
// ΔT/T × thickness / scale height (~1e−4 of P for 30 K over 20 m), which this neglects.
// Flat: z = y − groundHeight, ∇n = (0, dn/dz, 0). Round: z = |x − centre| − earthRadius,
// ∇n = dn/dz along the radius, and n = 1 above the shell.
class AtmosphereIndexField final : public IndexField {
public:
    explicit AtmosphereIndexField(AtmosphereSettings settings);

    void eval(const Vec3d& x, double lambdaNm, double* n, Vec3d* gradient) const override;
    double gradientBound(const Vec3d& lo, const Vec3d& hi) const override;
    // Round: a straight path runs to the shell's top sphere from outside it.
    double straightDistance(const Vec3d& x, const Vec3d& d, double maxDistance) const override;

    // Temperature (K) and its height derivative at geometric height z: layers included.
    void temperature(double z, double* T, double* dTdz) const;
    // n − 1 and its height derivative at geometric height z (the shell's fade included).
    void refractivity(double z, double lambdaNm, double* nm1, double* dnm1dz) const;
    // The Earth's centre (Round).
    Vec3d centre() const { return Vec3d(0, mSettings.groundHeight - mSettings.earthRadius, 0); }

private:
    // A bound of |d(n − 1)/dz| over heights [z0, z1].
    double heightGradientBound(double z0, double z1) const;
    // T and dT/dz at z from the 1976 sample there and dH/dz: the layers added.
    void addLayers(double z, const AtmosphereSample& std1976, double dHdz, double* T,
                   double* dTdz) const;
    AtmosphereSettings mSettings;
};

}  // namespace mirage
