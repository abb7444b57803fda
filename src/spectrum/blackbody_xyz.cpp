#include "spectrum/blackbody_xyz.h"

#include <array>
#include <cmath>

#include "spectrum/cie.h"
#include "spectrum/spectrum.h"

namespace mirage {

namespace {

constexpr double kTMin = 300.0, kTMax = 100000.0;
constexpr int kEntries = 2048;

// XYZ[B(·, T)] by spectrumToXyz's sum (1 nm steps over 360–830 nm, / ∫ȳ), in double: at 300 K
// the blue end of B is ~1e-51, below float's range.
Vec3d exactXyz(double kelvin) {
    Vec3d sum(0.0);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        const double l = kLambdaMin + double(i);
        sum += Vec3d(cieXyz(float(l))) * (planck(l, kelvin) * 1e-9);
    }
    return sum / double(kCieYIntegral);
}

struct Table {
    std::array<Vec3d, kEntries> logXyz;  // ln X, ln Y, ln Z at entry i
    double step = std::log(kTMax / kTMin) / (kEntries - 1);
    Table() {
        for (int i = 0; i < kEntries; ++i) {
            const Vec3d c = exactXyz(kTMin * std::exp(step * i));
            logXyz[size_t(i)] = Vec3d(std::log(c.x), std::log(c.y), std::log(c.z));
        }
    }
};

const Table& table() {
    static const Table t;  // built once, on first use (~5 ms)
    return t;
}

}  // namespace

Vec3 blackbodyXyz(float kelvin) {
    if (!(kelvin > 0.f)) return Vec3(0.f);
    if (kelvin < kTMin || kelvin > kTMax) return Vec3(exactXyz(kelvin));
    const Table& t = table();
    const double x = std::log(kelvin / kTMin) / t.step;
    const int i = std::min(int(x), kEntries - 2);
    const double f = x - i;
    const Vec3d a = t.logXyz[size_t(i)], b = t.logXyz[size_t(i) + 1];
    const Vec3d l = a + (b - a) * f;
    return Vec3(float(std::exp(l.x)), float(std::exp(l.y)), float(std::exp(l.z)));
}

}  // namespace mirage
