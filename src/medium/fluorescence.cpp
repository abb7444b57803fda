#include "medium/fluorescence.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mirage {

namespace {

// Below this allowed fraction of η no re-emission is attempted: the renormalised density
// would divide by a mass that float rounding dominates.
constexpr double kMinAllowedMass = 1e-9;

}  // namespace

Spectrum gaussianBand(float peakNm, float fwhmNm) {
    double s = fwhmNm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
    std::vector<float> v(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        double d = (kLambdaMin + i) - peakNm;
        v[i] = float(std::exp(-d * d / (2.0 * s * s)));
    }
    return Spectrum::fromDense(std::move(v));
}

FluorescenceEmission::FluorescenceEmission(float peakNm, float fwhmNm, bool antiStokes)
    : mSampler(gaussianBand(peakNm, fwhmNm)), mAntiStokes(antiStokes) {}

double FluorescenceEmission::forbiddenMass(float lambdaInNm) const {
    return mAntiStokes ? 0.0 : mSampler.cdf(lambdaInNm);
}

bool FluorescenceEmission::sample(float lambdaInNm, float u, float* lambdaOutNm,
                                  float* pdf) const {
    // Inverse CDF of η restricted to [λi, 830]: map u onto the allowed part of the CDF.
    double lo = forbiddenMass(lambdaInNm), allowed = 1.0 - lo;
    if (!(allowed > kMinAllowedMass)) return false;
    float l = mSampler.sample(float(lo + double(u) * allowed));
    // Rounding in the CDF inversion can land a hair below λi; the rule is exact.
    if (!mAntiStokes) l = std::max(l, lambdaInNm);
    *lambdaOutNm = l;
    if (pdf) *pdf = float(mSampler.pdf(l) / allowed);
    return true;
}

float FluorescenceEmission::pdf(float lambdaInNm, float lambdaOutNm) const {
    if (!mAntiStokes && lambdaOutNm < lambdaInNm) return 0.f;
    double allowed = 1.0 - forbiddenMass(lambdaInNm);
    if (!(allowed > kMinAllowedMass)) return 0.f;
    return float(mSampler.pdf(lambdaOutNm) / allowed);
}

}  // namespace mirage
