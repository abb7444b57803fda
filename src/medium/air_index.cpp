// The refractive index of air and the stratified atmosphere field (air_index.h says what).
#include "medium/air_index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace mirage {

namespace {

// US Standard Atmosphere 1976 layers: base geopotential height (m) and lapse rate (K/m)
// (../shared/data/README.md).
constexpr int kLayers = 7;
constexpr std::array<double, kLayers + 1> kBase = {0,     11000, 20000, 32000,
                                                   47000, 51000, 71000, 84852};
constexpr std::array<double, kLayers> kLapse = {-6.5e-3, 0, 1.0e-3, 2.8e-3, 0, -2.8e-3, -2.0e-3};
// g0 M / R: the hydrostatic constant, K/m.
constexpr double kHydro = air::kG0 * air::kMolarMass / air::kGasConstant;

struct LayerBase {
    double T, P;
};

// Temperature and pressure at every layer base, integrated once from T0 = 288.15 K and
// P0 = 101325 Pa: P = Pb (Tb / T)^(g0 M / (R L)) in a layer with lapse L, and
// P = Pb exp(−g0 M (H − Hb) / (R Tb)) in an isothermal one.
const std::array<LayerBase, kLayers + 1>& layerBases() {
    static const std::array<LayerBase, kLayers + 1> bases = [] {
        std::array<LayerBase, kLayers + 1> b{};
        b[0] = {288.15, 101325.0};
        for (int i = 0; i < kLayers; ++i) {
            const double dH = kBase[i + 1] - kBase[i];
            const double T = b[i].T + kLapse[i] * dH;
            const double P = kLapse[i] == 0 ? b[i].P * std::exp(-kHydro * dH / b[i].T)
                                            : b[i].P * std::pow(b[i].T / T, kHydro / kLapse[i]);
            b[i + 1] = {T, P};
        }
        return b;
    }();
    return bases;
}

// The C² step S(t) = 6t⁵ − 15t⁴ + 10t³ on [0, 1] (0 below, 1 above) and its derivative.
std::pair<double, double> smootherstep(double t) {
    if (t <= 0) return {0.0, 0.0};
    if (t >= 1) return {1.0, 0.0};
    return {t * t * t * (t * (6 * t - 15) + 10), 30 * t * t * (t - 1) * (t - 1)};
}

// The Fermi distribution F(t) = 1/(1 + e^(−t)) and its derivative F(1 − F).
std::pair<double, double> fermiStep(double t) {
    const double f = 1.0 / (1.0 + std::exp(-t));
    return {f, f * (1.0 - f)};
}

// A layer edge's step at t = (z − edge)/blend and its derivative in t; the smooth step is
// centred on the edge (t from −1/2 to 1/2).
std::pair<double, double> edgeStep(LayerEdge edge, double t) {
    return edge == LayerEdge::Fermi ? fermiStep(t) : smootherstep(t + 0.5);
}

// The largest slope of an edge's step in t: 15/8 for the smooth step, 1/4 for Fermi's.
double edgeSlopeMax(LayerEdge edge) { return edge == LayerEdge::Fermi ? 0.25 : 1.875; }

// dH/dz = (r0 / (r0 + z))², the geopotential height's slope at geometric height z.
double geopotentialSlope(double z) {
    const double q = air::kEarthRadius / (air::kEarthRadius + z);
    return q * q;
}

}  // namespace

double airDensity(double pressurePa, double temperatureK) {
    return pressurePa * air::kMolarMass / (air::kGasConstant * temperatureK);
}

double airRefractivity(double lambdaNm, double a, double bUm2) {
    const double um = lambdaNm * 1e-3;
    return a * (1.0 + bUm2 / (um * um));
}

double airIndex(double pressurePa, double temperatureK, double lambdaNm, AirDispersion dispersion) {
    return 1.0 + airDensity(pressurePa, temperatureK) / referenceDensity(dispersion) *
                     referenceRefractivity(dispersion, lambdaNm);
}

AtmosphereSample usStandardAtmosphere1976(double H) {
    const auto& b = layerBases();
    // Above the model's top (84.852 km) the air is continued isothermally at the top's
    // temperature, P = P_top exp(−g0 M (H − H_top) / (R T_top)): the top layer's lapse rate
    // extended upwards would reach 0 K near H = 178 km and give a NaN index to every ray or
    // photon that starts far away (a distant light's photons start ~10⁸ m out).
    if (H > kBase[kLayers]) {
        const LayerBase& top = b[kLayers];
        const double P = top.P * std::exp(-kHydro * (H - kBase[kLayers]) / top.T);
        return {top.T, P, airDensity(P, top.T), 0.0};
    }
    int i = 0;
    while (i + 1 < kLayers && H >= kBase[i + 1]) ++i;
    const double dH = H - kBase[i];  // negative below sea level: layer 0 extended downwards
    const double T = b[i].T + kLapse[i] * dH;
    const double P = kLapse[i] == 0 ? b[i].P * std::exp(-kHydro * dH / b[i].T)
                                    : b[i].P * std::pow(b[i].T / T, kHydro / kLapse[i]);
    return {T, P, airDensity(P, T), kLapse[i]};
}

AtmosphereIndexField::AtmosphereIndexField(AtmosphereSettings settings)
    : mSettings(std::move(settings)) {}

void AtmosphereIndexField::temperature(double z, double* T, double* dTdz) const {
    addLayers(z, usStandardAtmosphere1976(geopotentialHeight(z)), geopotentialSlope(z), T, dTdz);
}

// The 1976 sample at z is passed in: eval needs it for the pressure too, and its power law is
// the field's costliest part (a curved camera ray evaluates the field thousands of times).
void AtmosphereIndexField::addLayers(double z, const AtmosphereSample& std1976, double dHdz,
                                     double* T, double* dTdz) const {
    *T = std1976.temperature;
    *dTdz = std1976.dTdH * dHdz;
    // Each layer is the difference of two blended steps: up at the base, down at the top.
    for (const InversionLayer& l : mSettings.inversions) {
        const auto up = edgeStep(l.edge, (z - l.base) / l.blend);
        const auto down = edgeStep(l.edge, (z - l.top) / l.blend);
        *T += l.deltaT * (up.first - down.first);
        *dTdz += l.deltaT * (up.second - down.second) / l.blend;
    }
}

void AtmosphereIndexField::refractivity(double z, double lambdaNm, double* nm1,
                                        double* dnm1dz) const {
    const double dHdz = geopotentialSlope(z);
    const AtmosphereSample std1976 = usStandardAtmosphere1976(geopotentialHeight(z));
    double T, dTdz;
    addLayers(z, std1976, dHdz, &T, &dTdz);
    // n − 1 = K P / T, so d(n−1)/dz = (n−1)(P'/P − T'/T), with the hydrostatic
    // P'/P = −g0 M / (R T_1976) · dH/dz of the standard atmosphere's own pressure.
    *nm1 = airIndex(std1976.pressure, T, lambdaNm, mSettings.dispersion) - 1.0;
    const double dlnP = -kHydro / std1976.temperature * dHdz;
    *dnm1dz = *nm1 * (dlnP - dTdz / T);
    if (mSettings.earth == EarthShape::Flat) return;
    // The shell's top: n − 1 faded to 0 over its last kilometre.
    const auto fade = smootherstep((z - mSettings.shellDepth) / air::kShellFade + 1.0);
    *dnm1dz = *dnm1dz * (1.0 - fade.first) - *nm1 * fade.second / air::kShellFade;
    *nm1 *= 1.0 - fade.first;
}

void AtmosphereIndexField::eval(const Vec3d& x, double lambdaNm, double* n, Vec3d* gradient) const {
    double nm1, dnm1dz;
    if (mSettings.earth == EarthShape::Flat) {
        refractivity(x.y - mSettings.groundHeight, lambdaNm, &nm1, &dnm1dz);
        *n = 1.0 + nm1;
        *gradient = Vec3d(0, dnm1dz, 0);
        return;
    }
    const Vec3d radial = x - centre();
    const double r = length(radial);
    if (r - mSettings.earthRadius >= mSettings.shellDepth) {
        *n = 1.0;
        *gradient = Vec3d(0, 0, 0);
        return;
    }
    refractivity(r - mSettings.earthRadius, lambdaNm, &nm1, &dnm1dz);
    *n = 1.0 + nm1;
    *gradient = radial * (dnm1dz / r);
}

double AtmosphereIndexField::straightDistance(const Vec3d& x, const Vec3d& d,
                                              double maxDistance) const {
    if (mSettings.earth == EarthShape::Flat) return 0.0;
    // Outside the shell's top sphere (radius R + depth) n is 1: straight up to where the line
    // x + t d meets that sphere, t² + 2 b t + c = 0 with b = (x − centre)·d.
    const Vec3d o = x - centre();
    const double top = mSettings.earthRadius + mSettings.shellDepth;
    const double c = dot(o, o) - top * top;
    if (!(c > 0)) return 0.0;
    const double b = dot(o, d), disc = b * b - c;
    if (b >= 0 || disc <= 0) return maxDistance;               // heading away, or passing it by
    return std::min(maxDistance, c / (-b + std::sqrt(disc)));  // the near root, stably
}

double AtmosphereIndexField::gradientBound(const Vec3d& lo, const Vec3d& hi) const {
    if (mSettings.earth == EarthShape::Flat)
        return heightGradientBound(lo.y - mSettings.groundHeight, hi.y - mSettings.groundHeight);
    // The heights over the box: from its point nearest the centre to its farthest corner.
    // |∇n| = |d(n − 1)/dz| along the radius.
    const Vec3d c = centre();
    Vec3d nearest, farthest;
    for (int a = 0; a < 3; ++a) {
        nearest[a] = std::clamp(c[a], lo[a], hi[a]);
        farthest[a] = std::abs(lo[a] - c[a]) > std::abs(hi[a] - c[a]) ? lo[a] : hi[a];
    }
    const double z0 = length(nearest - c) - mSettings.earthRadius;
    if (z0 >= mSettings.shellDepth) return 0.0;
    const double z1 = std::min(length(farthest - c) - mSettings.earthRadius, mSettings.shellDepth);
    return heightGradientBound(z0, z1);
}

double AtmosphereIndexField::heightGradientBound(double zLo, double zHi) const {
    // |dn/dz| ≤ (n−1)max · (|P'/P|max + |T'|max / Tmin): each factor bounded over [z0, z1].
    // The geopotential height R z / (R + z) turns back up below z = −R (through the Earth's
    // centre), where the model means nothing anyway: heights are floored at −R/2, still far
    // below any ground, so a whole-space query (±1e30 m) bounds the densest air there is.
    const double zFloor = -0.5 * air::kEarthRadius;
    const double z0 = std::max(zLo, zFloor);
    const double z1 = std::max(zHi, zFloor);
    const double H0 = geopotentialHeight(z0), H1 = geopotentialHeight(z1);
    // The 1976 temperature is piecewise linear in H: its minimum is at an end or a layer base.
    double tStdMin = std::min(usStandardAtmosphere1976(H0).temperature,
                              usStandardAtmosphere1976(H1).temperature);
    for (double Hb : kBase)
        if (Hb > H0 && Hb < H1)
            tStdMin = std::min(tStdMin, usStandardAtmosphere1976(Hb).temperature);
    const double dHdzMax = geopotentialSlope(std::min(z0, 0.0));
    double coldest = 0, dTmax = 6.5e-3 * dHdzMax;  // every 1976 lapse rate is ≤ 6.5 K/km
    for (const InversionLayer& l : mSettings.inversions) {
        coldest += std::min(0.0, l.deltaT);
        dTmax += std::abs(l.deltaT) * edgeSlopeMax(l.edge) / l.blend;
    }
    const double tMin = tStdMin + coldest;
    if (!(tMin > 0)) return kInfinity;
    const double pMax = usStandardAtmosphere1976(H0).pressure;  // P falls with height
    // Refractivity grows to blue in every dispersion formula.
    const double nm1Max = airIndex(pMax, tMin, 360.0, mSettings.dispersion) - 1.0;
    const double bound = nm1Max * (kHydro / tStdMin * dHdzMax + dTmax / tMin);
    // Round: the fade at the shell's top adds (n − 1)·|fade'| ≤ (n − 1)max · (15/8) / fade.
    const bool fading =
        mSettings.earth == EarthShape::Round && z1 > mSettings.shellDepth - air::kShellFade;
    return fading ? bound + nm1Max * 1.875 / air::kShellFade : bound;
}

}  // namespace mirage
