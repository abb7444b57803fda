#include "spectrum/spectrum_sampling.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace mirage {

SpectrumSampler::SpectrumSampler(const Spectrum& s) {
    const int n = Spectrum::kDenseSamples;
    mValue.resize(n);
    for (int i = 0; i < n; ++i) mValue[i] = std::max(0.f, s(kLambdaMin + float(i)));
    // Trapezoids are exact for a piecewise-linear S.
    mCdf.resize(n);
    mCdf[0] = 0.0;
    for (int i = 1; i < n; ++i) mCdf[i] = mCdf[i - 1] + 0.5 * (double(mValue[i - 1]) + mValue[i]);
    mIntegral = mCdf[n - 1];
    if (!(mIntegral > 0.0))
        throw MirageError("spectrum has no energy in 360–830 nm: no wavelength can be sampled");
}

float SpectrumSampler::sample(float u, float* pdf) const {
    MIRAGE_DCHECK(valid());
    // Target area r in [0, ∫S); the interval [i, i+1] nm whose cumulative area brackets it.
    // Intervals of zero area are never chosen: upper_bound skips equal CDF entries.
    double r = clamp(double(u), 0.0, 1.0) * mIntegral;
    int last = int(mCdf.size()) - 1;
    int i = int(std::upper_bound(mCdf.begin(), mCdf.end(), r) - mCdf.begin()) - 1;
    i = clamp(i, 0, last - 1);
    while (i > 0 && mCdf[i + 1] == mCdf[i]) --i;  // u = 1 lands past a zero-area tail
    double a = mValue[i], b = mValue[i + 1];
    r = clamp(r - mCdf[i], 0.0, 0.5 * (a + b));
    // Within the interval S(x) = a + (b − a) x, x ∈ [0, 1], and ∫₀ˣ S = a x + (b − a) x²/2 = r.
    // The root in [0, 1], written as 2r / (a + √(a² + 2(b − a) r)) so that it neither cancels
    // when b ≈ a nor divides by zero when a = 0.
    double disc = std::max(0.0, a * a + 2.0 * (b - a) * r);
    double denom = a + std::sqrt(disc);
    double x = denom > 0.0 ? clamp(2.0 * r / denom, 0.0, 1.0) : 0.5;
    float lambda = kLambdaMin + float(i) + float(x);
    if (pdf) *pdf = float((a + (b - a) * x) / mIntegral);
    return std::min(lambda, kLambdaMax);
}

float SpectrumSampler::pdf(float lambdaNm) const {
    if (!(lambdaNm >= kLambdaMin && lambdaNm <= kLambdaMax) || !valid()) return 0.f;
    float t = lambdaNm - kLambdaMin;
    int i = std::min(int(t), int(mValue.size()) - 2);
    return float(lerp(double(t) - i, double(mValue[i]), double(mValue[i + 1])) / mIntegral);
}

double SpectrumSampler::cdf(float lambdaNm) const {
    if (!valid() || !(lambdaNm > kLambdaMin)) return 0.0;
    if (lambdaNm >= kLambdaMax) return 1.0;
    // The partial interval is the same quadratic area as in sample(): a x + (b − a) x²/2.
    float t = lambdaNm - kLambdaMin;
    int i = std::min(int(t), int(mValue.size()) - 2);
    double x = double(t) - i, a = mValue[i], b = mValue[i + 1];
    return (mCdf[i] + a * x + 0.5 * (b - a) * x * x) / mIntegral;
}

float sampleWavelength(const Spectrum& s, float u, float* pdf) {
    return SpectrumSampler(s).sample(u, pdf);
}

}  // namespace mirage
