// Spectra stored densely at 1 nm, the blackbody, and the two RGB → spectrum mappings.

#include "spectrum/spectrum.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "spectrum/cie.h"

namespace mirage {

namespace {

float denseLambda(int i) { return kLambdaMin + float(i); }

// The RGB basis: three smooth windows made of two logistic steps,
//   s₁(λ) = σ((λ − 490 nm) / w),  s₂(λ) = σ((λ − 590 nm) / w),  σ(x) = 1 / (1 + e⁻ˣ),
//   B_b = 1 − s₁,  B_g = s₁ − s₂,  B_r = s₂,
// so B_b + B_g + B_r = 1 exactly and each window lies in [0, 1] (s₁ ≥ s₂ everywhere because
// both are the same increasing function, shifted). The cross-overs at 490 and 590 nm sit between
// the dominant wavelengths of the Rec.709/AP1 primaries (blue ≈ 465 nm, green 530–550 nm, red
// 610–620 nm) and close to where z̄ gives way to ȳ (≈ 500 nm) and ȳ to x̄ (≈ 575 nm), so each
// window maps mostly onto one primary. w = 15 nm is the logistic scale: a cross-over takes
// ≈ 66 nm from 10 % to 90 % (2 ln 9 · w). Narrower windows reach more saturated colours but make
// spectra with steep edges that 4 wavelength samples per path resolve poorly (more colour
// noise); wider ones blur the three windows into each other. Natural reflectances are smooth on
// this scale (Maloney 1986, JOSA A 3(10): a few smooth basis functions describe them well).
constexpr double kBlueGreenNm = 490.0, kGreenRedNm = 590.0, kBasisScaleNm = 15.0;

double logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }

struct BasisSteps {
    double s1, s2;
};

BasisSteps basisSteps(double lambdaNm) {
    return {logistic((lambdaNm - kBlueGreenNm) / kBasisScaleNm),
            logistic((lambdaNm - kGreenRedNm) / kBasisScaleNm)};
}

// The windows in r, g, b order.
Vec3d basis(double lambdaNm) {
    BasisSteps s = basisSteps(lambdaNm);
    return {s.s2, s.s1 - s.s2, 1.0 - s.s1};
}

}  // namespace

// --- Spectrum ------------------------------------------------------------------------------

Spectrum Spectrum::fromDense(std::vector<float> values1nm) {
    MIRAGE_CHECK(values1nm.size() == size_t(kDenseSamples));
    Spectrum s;
    s.mTable = std::move(values1nm);
    return s;
}

Spectrum Spectrum::fromTable(const std::vector<float>& lambdaNm, const std::vector<float>& value) {
    if (lambdaNm.empty() || lambdaNm.size() != value.size())
        throw MirageError("spectrum table: expected as many values as wavelengths (got " +
                          std::to_string(lambdaNm.size()) + " wavelengths and " +
                          std::to_string(value.size()) + " values)");
    for (size_t i = 0; i < lambdaNm.size(); ++i) {
        if (!std::isfinite(lambdaNm[i]) || !std::isfinite(value[i]))
            throw MirageError("spectrum table: entry " + std::to_string(i) + " is not finite");
        if (i > 0 && !(lambdaNm[i] > lambdaNm[i - 1]))
            throw MirageError("spectrum table: wavelengths must increase (entry " +
                              std::to_string(i) + ": " + std::to_string(lambdaNm[i]) +
                              " nm after " + std::to_string(lambdaNm[i - 1]) + " nm)");
    }
    if (lambdaNm.size() == 1) return Spectrum(value[0]);

    std::vector<float> dense(kDenseSamples);
    for (int i = 0; i < kDenseSamples; ++i) {
        float l = denseLambda(i);
        auto hi = std::upper_bound(lambdaNm.begin(), lambdaNm.end(), l);
        if (hi == lambdaNm.begin()) {
            dense[i] = value.front();
        } else if (hi == lambdaNm.end()) {
            dense[i] = value.back();
        } else {
            size_t j = size_t(hi - lambdaNm.begin());
            float t = (l - lambdaNm[j - 1]) / (lambdaNm[j] - lambdaNm[j - 1]);
            dense[i] = lerp(t, value[j - 1], value[j]);
        }
    }
    return fromDense(std::move(dense));
}

float Spectrum::operator()(float lambdaNm) const {
    if (mTable.empty()) return mConstant;
    // Clamped to the table, NaN to its start, so a stray wavelength cannot read out of bounds.
    float t = lambdaNm > kLambdaMin
                  ? (lambdaNm < kLambdaMax ? lambdaNm - kLambdaMin : kLambdaMax - kLambdaMin)
                  : 0.f;
    int i = std::min(int(t), kDenseSamples - 2);
    return lerp(t - float(i), mTable[i], mTable[i + 1]);
}

SampledSpectrum Spectrum::sample(const SampledWavelengths& w) const {
    if (mTable.empty()) return SampledSpectrum(mConstant);
    SampledSpectrum r;
    for (int i = 0; i < kSpectrumSamples; ++i) r[i] = (*this)(w.lambda[i]);
    return r;
}

float Spectrum::maxValue() const {
    return mTable.empty() ? mConstant : *std::max_element(mTable.begin(), mTable.end());
}

Spectrum Spectrum::scaled(float s) const {
    Spectrum r = *this;
    r.mConstant *= s;
    for (float& v : r.mTable) v *= s;
    return r;
}

// --- Blackbody -----------------------------------------------------------------------------

// Planck's law B_λ(T) = 2hc² / λ⁵ / (exp(hc / (λ k_B T)) − 1) with the exact SI constants of the
// 2019 redefinition (CODATA 2018). expm1 keeps full precision where hc/(λkT) is small (very hot
// bodies, Rayleigh–Jeans regime); where it exceeds 700, exp would overflow a double (e^709.8) and
// the true radiance is below 1e-280 of the peak, so it is 0. Double precision throughout: at
// 1e5 K the values reach 1e21.
double planck(double lambdaNm, double temperatureK) {
    constexpr double kH = 6.62607015e-34;  // Planck constant, J·s
    constexpr double kC = 299792458.0;     // speed of light, m/s
    constexpr double kKb = 1.380649e-23;   // Boltzmann constant, J/K
    if (!(temperatureK > 0.0) || !(lambdaNm > 0.0)) return 0.0;
    double lambda = lambdaNm * 1e-9;  // m
    double x = kH * kC / (lambda * kKb * temperatureK);
    if (x > 700.0) return 0.0;
    double lambda5 = lambda * lambda * lambda * lambda * lambda;
    return 2.0 * kH * kC * kC / (lambda5 * std::expm1(x));
}

Spectrum blackbodyNormalized(float temperatureK) {
    std::vector<double> b(Spectrum::kDenseSamples);
    double peak = 0.0;
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        b[i] = planck(denseLambda(i), temperatureK);
        peak = std::max(peak, b[i]);
    }
    // Too cold to emit in the visible range at double precision (below ≈ 30 K): no colour.
    if (!(peak > 0.0)) return Spectrum(0.f);
    std::vector<float> dense(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) dense[i] = float(b[i] / peak);
    return Spectrum::fromDense(std::move(dense));
}

// --- RGB → spectrum ------------------------------------------------------------------------

// S(λ) = r B_r + g B_g + b B_b = b + (g − b) s₁ + (r − g) s₂: a convex combination of r, g, b at
// every wavelength. Grey maps to a constant Spectrum, not a flat table, so a grey albedo leaves a
// medium wavelength-independent and the renderer can take its cheaper non-spectral path.
Spectrum rgbReflectanceSpectrum(const Vec3& rgb) {
    if (rgb.x == rgb.y && rgb.y == rgb.z) return Spectrum(rgb.x);
    double lo = std::min({rgb.x, rgb.y, rgb.z}), hi = std::max({rgb.x, rgb.y, rgb.z});
    std::vector<float> dense(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        BasisSteps s = basisSteps(denseLambda(i));
        double v = rgb.z + (double(rgb.y) - rgb.z) * s.s1 + (double(rgb.x) - rgb.y) * s.s2;
        // Mathematically a no-op; it keeps rounding from stepping outside [min, max] of the input.
        dense[i] = float(clamp(v, lo, hi));
    }
    return Spectrum::fromDense(std::move(dense));
}

// Find c = (c_r, c_g, c_b) with xyzToWorking · XYZ(Σ c_k B_k) = rgb. XYZ is linear in the
// spectrum, so with A = [XYZ(B_r) XYZ(B_g) XYZ(B_b)] (columns) this is the 3×3 system
// (xyzToWorking · A) c = rgb. Colours outside the gamut the three windows can make (very
// saturated ones) need a negative coefficient; an emitter cannot emit negative power, so those
// are clamped to 0 and the colour comes out desaturated.
Mat3 rgbIlluminantCoefficients(const Mat3& xyzToWorking) {
    Mat3 a;
    a.m.fill(0.0);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        Vec3d cmf(cieXyz(denseLambda(i)));
        Vec3d b = basis(denseLambda(i));
        for (int row = 0; row < 3; ++row)
            for (int k = 0; k < 3; ++k) a(row, k) += cmf[row] * b[k];
    }
    for (double& v : a.m) v /= double(kCieYIntegral);
    Mat3 system = xyzToWorking * a;
    MIRAGE_CHECK(std::abs(system.determinant()) > 1e-12);
    return system.inverse();
}

Spectrum rgbBasisSpectrum(int k) {
    MIRAGE_CHECK(k >= 0 && k < 3);
    std::vector<float> dense(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) dense[i] = float(basis(denseLambda(i))[k]);
    return Spectrum::fromDense(std::move(dense));
}

Spectrum rgbIlluminantSpectrum(const Vec3& rgb, const Mat3& xyzToWorking) {
    const Vec3d c = vmax(rgbIlluminantCoefficients(xyzToWorking).apply(Vec3d(rgb)), Vec3d(0.0));
    std::vector<float> dense(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i)
        dense[i] = float(dot(c, basis(denseLambda(i))));
    return Spectrum::fromDense(std::move(dense));
}

Vec3d spectrumToXyz(const Spectrum& s) {
    Vec3d sum(0.0);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        float l = denseLambda(i);
        sum += Vec3d(cieXyz(l)) * double(s(l));
    }
    return sum / double(kCieYIntegral);
}

}  // namespace mirage
