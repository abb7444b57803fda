// The astronomers' refraction, what the round-Earth atmosphere is tested against: Bennett 1982
// (Journal of Navigation 35, 255; as in Meeus, Astronomical Algorithms, ch. 16),
//     R = cot(h + 7.31/(h + 4.4)) arcminutes at apparent altitude h (degrees),
// for 10 °C and 101.0 kPa and within 0.07′ of Garfinkel's tables; other states scale it by
// (P/101 kPa)(283 K/T). Here it is scaled to the US Standard Atmosphere's ground, 101.325 kPa
// and 288.15 K. Published examples: 34.5′ at the horizon, 24.3′ at 1°, 9.9′ at 5°, 5.3′ at 10°
// (at 10 °C, 101.0 kPa).
#pragma once

#include <cmath>
#include <functional>

namespace mirage::test {

inline double bennettArcmin(double hDeg) {
    constexpr double kDeg = M_PI / 180;
    const double scale = (101.325 / 101.0) * (283.0 / 288.15);
    return scale / std::tan((hDeg + 7.31 / (hDeg + 4.4)) * kDeg);
}

// The apparent altitude (degrees) of a point at true altitude `trueDeg`, h − R(h) = true, by
// bisection, for a refraction R in arcminutes (Bennett's by default).
inline double apparentAltitude(
    double trueDeg, const std::function<double(double)>& refractionArcmin = bennettArcmin) {
    double lo = trueDeg, hi = trueDeg + 1.0;
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (mid - refractionArcmin(mid) / 60 > trueDeg ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace mirage::test
