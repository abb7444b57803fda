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
    : mRows{SpectrumSampler(gaussianBand(peakNm, fwhmNm))}, mAntiStokes(antiStokes) {}

FluorescenceEmission::FluorescenceEmission(const EmissionMatrix& matrix, bool antiStokes)
    : mExcitationNm(matrix.excitationNm), mAntiStokes(antiStokes) {
    for (const Spectrum& row : matrix.rows) mRows.emplace_back(row);
}

FluorescenceEmission::RowBlend FluorescenceEmission::blendAt(float lambdaInNm) const {
    RowBlend b;
    const size_t n = mExcitationNm.size();
    if (n < 2 || lambdaInNm <= mExcitationNm.front()) return b;
    if (lambdaInNm >= mExcitationNm.back()) {
        b.row[0] = b.row[1] = int(n - 1);
        return b;
    }
    const size_t k =
        size_t(std::upper_bound(mExcitationNm.begin(), mExcitationNm.end(), lambdaInNm) -
               mExcitationNm.begin()) -
        1;
    const float t = (lambdaInNm - mExcitationNm[k]) / (mExcitationNm[k + 1] - mExcitationNm[k]);
    b.row[0] = int(k);
    b.row[1] = int(k + 1);
    b.weight[0] = 1.f - t;
    b.weight[1] = t;
    return b;
}

double FluorescenceEmission::forbiddenMass(int row, float lambdaInNm) const {
    return mAntiStokes ? 0.0 : mRows[size_t(row)].cdf(lambdaInNm);
}

double FluorescenceEmission::allowedTotal(const RowBlend& b, float lambdaInNm) const {
    double total = b.weight[0] * allowedMass(b.row[0], lambdaInNm);
    if (b.weight[1] > 0.f) total += b.weight[1] * allowedMass(b.row[1], lambdaInNm);
    return total;
}

bool FluorescenceEmission::sample(float lambdaInNm, float u, float* lambdaOutNm, float* pdf) const {
    const RowBlend b = blendAt(lambdaInNm);
    const double total = allowedTotal(b, lambdaInNm);
    if (!(total > kMinAllowedMass)) return false;
    // The row, with probability ∝ weight × allowed mass, and u rescaled within its share.
    int k = 0;
    if (b.weight[1] > 0.f) {
        const double first = b.weight[0] * allowedMass(b.row[0], lambdaInNm) / total;
        k = double(u) < first ? 0 : 1;
        u = float(k == 0 ? double(u) / first : (double(u) - first) / (1.0 - first));
        u = std::min(u, 1.f);
    }
    // Inverse CDF of the row restricted to [λi, 830]: map u onto the allowed part of its CDF.
    const double lo = forbiddenMass(b.row[k], lambdaInNm), allowed = 1.0 - lo;
    float l = mRows[size_t(b.row[k])].sample(float(lo + double(u) * allowed));
    // Rounding in the CDF inversion can land a hair below λi; the rule is exact.
    if (!mAntiStokes) l = std::max(l, lambdaInNm);
    *lambdaOutNm = l;
    if (pdf) *pdf = this->pdf(lambdaInNm, l);
    return true;
}

float FluorescenceEmission::pdf(float lambdaInNm, float lambdaOutNm) const {
    if (!mAntiStokes && lambdaOutNm < lambdaInNm) return 0.f;
    const RowBlend b = blendAt(lambdaInNm);
    const double total = allowedTotal(b, lambdaInNm);
    if (!(total > kMinAllowedMass)) return 0.f;
    double density = b.weight[0] * double(mRows[size_t(b.row[0])].pdf(lambdaOutNm));
    if (b.weight[1] > 0.f)
        density += b.weight[1] * double(mRows[size_t(b.row[1])].pdf(lambdaOutNm));
    return float(density / total);
}

}  // namespace mirage
