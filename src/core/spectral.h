// Spectral samples carried by every path: 4 wavelengths per path (hero wavelength sampling,
// Wilkie et al. 2014) and the spectral quantities evaluated at them. Wavelengths in nm.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"

namespace mirage {

constexpr int kSpectrumSamples = 4;
constexpr float kLambdaMin = 360.f, kLambdaMax = 830.f;  // CIE 1931 support (nm)

class SampledSpectrum {
public:
    SampledSpectrum() { v.fill(0.f); }
    explicit SampledSpectrum(float c) { v.fill(c); }
    float operator[](int i) const { return v[i]; }
    float& operator[](int i) { return v[i]; }

#define MIRAGE_SPEC_OP(op)                                              \
    SampledSpectrum operator op(const SampledSpectrum& o) const {       \
        SampledSpectrum r;                                              \
        for (int i = 0; i < kSpectrumSamples; ++i) r.v[i] = v[i] op o.v[i]; \
        return r;                                                       \
    }                                                                   \
    SampledSpectrum& operator op##=(const SampledSpectrum& o) {         \
        for (int i = 0; i < kSpectrumSamples; ++i) v[i] op## = o.v[i];  \
        return *this;                                                   \
    }                                                                   \
    SampledSpectrum operator op(float s) const {                        \
        SampledSpectrum r;                                              \
        for (int i = 0; i < kSpectrumSamples; ++i) r.v[i] = v[i] op s;  \
        return r;                                                       \
    }                                                                   \
    SampledSpectrum& operator op##=(float s) {                          \
        for (int i = 0; i < kSpectrumSamples; ++i) v[i] op## = s;       \
        return *this;                                                   \
    }
    MIRAGE_SPEC_OP(+)
    MIRAGE_SPEC_OP(-)
    MIRAGE_SPEC_OP(*)
    MIRAGE_SPEC_OP(/)
#undef MIRAGE_SPEC_OP

    float maxValue() const { return std::max(std::max(v[0], v[1]), std::max(v[2], v[3])); }
    float minValue() const { return std::min(std::min(v[0], v[1]), std::min(v[2], v[3])); }
    float average() const { return (v[0] + v[1] + v[2] + v[3]) * 0.25f; }
    bool isZero() const { return v[0] == 0.f && v[1] == 0.f && v[2] == 0.f && v[3] == 0.f; }
    bool isFinite() const {
        return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) &&
               std::isfinite(v[3]);
    }

private:
    std::array<float, kSpectrumSamples> v;
};

inline SampledSpectrum operator*(float s, const SampledSpectrum& a) { return a * s; }
inline SampledSpectrum exp(const SampledSpectrum& a) {
    // Grey media give the same value at every wavelength (Beer–Lambert factors, the shadow
    // rays' controls): one exp then, the same bits, a quarter of the work.
    if (a[0] == a[1] && a[0] == a[2] && a[0] == a[3]) return SampledSpectrum(std::exp(a[0]));
    SampledSpectrum r;
    for (int i = 0; i < kSpectrumSamples; ++i) r[i] = std::exp(a[i]);
    return r;
}
// 0/0 = 0: a quantity whose sampling density vanished contributes nothing.
inline SampledSpectrum safeDiv(const SampledSpectrum& a, const SampledSpectrum& b) {
    SampledSpectrum r;
    for (int i = 0; i < kSpectrumSamples; ++i) r[i] = b[i] != 0.f ? a[i] / b[i] : 0.f;
    return r;
}

// The wavelengths of one path and the density they were drawn with (1/nm).
struct SampledWavelengths {
    std::array<float, kSpectrumSamples> lambda{};
    std::array<float, kSpectrumSamples> pdf{};

    // Importance sampling of the visible range with p(λ) ∝ 1/cosh²(0.0072(λ−538)) on
    // [360, 830] nm (Radziszewski et al. 2009, as used by pbrt-v4): close to the sum of the CIE
    // matching functions, so the XYZ estimate has low variance. The 4 samples are stratified by
    // rotating u by 1/4 (hero wavelength sampling). The density of a drawn λ comes from y, the
    // atanh's argument: 0.0072 · 138.888889 = 1, so cosh(0.0072 (λ − 538)) = cosh(atanh y) =
    // 1/√(1 − y²) and p(λ) = 0.0039398042 (1 − y²), visiblePdf without its cosh (every camera
    // sample draws four; |y| ≤ 0.971 over [0, 1), so 1 − y² ≥ 0.057 loses no precision).
    static SampledWavelengths sampleVisible(float u) {
        SampledWavelengths w;
        for (int i = 0; i < kSpectrumSamples; ++i) {
            float up = u + float(i) / kSpectrumSamples;
            if (up >= 1.f) up -= 1.f;
            const float y = visibleArgument(up);
            // atanh y = ½ ln((1 + y)/(1 − y)): logf is table-driven, glibc's atanhf goes
            // through the slower log1pf. The ratio lies in [0.015, 13], its rounding a few ulps
            // of λ; u = 0 gives 360.0002 nm, so the clamp only keeps rounding inside the range.
            const float lambda = 538.f - 69.4444445f * std::log((1.f + y) / (1.f - y));
            w.lambda[i] = std::min(kLambdaMax, std::max(kLambdaMin, lambda));
            w.pdf[i] = 0.0039398042f * (1.f - y * y);
        }
        return w;
    }
    static float visiblePdf(float lambda) {
        if (lambda < kLambdaMin || lambda > kLambdaMax) return 0.f;
        float c = std::cosh(0.0072f * (lambda - 538.f));
        return 0.0039398042f / (c * c);
    }
    static float visibleArgument(float u) { return 0.85691062f - 1.82750197f * u; }
};

}  // namespace mirage
