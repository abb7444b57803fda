// What the light types share beyond the Light interface (light.h): the integral of a spectral
// power distribution, and vectors and numbers as text for describe().
#pragma once

#include <string>

#include "core/math.h"
#include "spectrum/spectrum.h"

namespace mirage {

// ∫ S dλ over 360–830 nm (trapezoids at 1 nm).
double powerIntegral(const Spectrum& s);

// "(x, y, z)".
std::string vecStr(const Vec3& v);
// A number for describe(): six significant digits, no trailing zeros ("4e+06", "2", "0.25").
std::string numStr(double v);

}  // namespace mirage
