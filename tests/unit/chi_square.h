// Pearson's χ² goodness-of-fit test for the sampling tests (every sampling routine gets one,
// STYLE.md): observed histogram counts against the counts its density predicts.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace mirage::test {

struct ChiSquare {
    double statistic = 0;
    int dof = 0;  // bins used − 1
};

// Bins that expect fewer than 5 counts are pooled into one (Cochran's rule), so that every
// term is close to its χ² limit.
inline ChiSquare chiSquare(const std::vector<double>& observed,
                           const std::vector<double>& expected) {
    ChiSquare r;
    double pooledObs = 0, pooledExp = 0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5) {
            pooledObs += observed[i];
            pooledExp += expected[i];
            continue;
        }
        r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++bins;
    }
    if (pooledExp >= 5) {
        r.statistic += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
        ++bins;
    }
    r.dof = bins - 1;
    return r;
}

// The 99.9 % quantile of χ² with k degrees of freedom, by the Wilson–Hilferty cube-root
// approximation k (1 − 2/(9k) + z √(2/(9k)))³ with z = 3.0902 (the normal 99.9 % quantile);
// within 1 % of the exact quantile for k ≥ 5.
inline double chiSquareCritical(int k) {
    double a = 2.0 / (9.0 * k);
    double c = 1.0 - a + 3.0902 * std::sqrt(a);
    return k * c * c * c;
}

// Pearson's χ² of a direction sampler against its density on an equal-area grid of the sphere
// (kZ bands of z × kPhi sectors of φ), and ∫ pdf dω by the midpoint rule over kSub² sub-cells
// per bin (a density that jumps needs more of them where it is seen small). draw() gives one
// unit direction, pdf(d) its density (1/sr).
struct SphereChiSquare {
    ChiSquare fit;
    double integral = 0;
};
template <int kZ, int kPhi, int kSub, typename Draw, typename Pdf>
SphereChiSquare sphereChiSquare(int draws, Draw&& draw, Pdf&& pdf) {
    constexpr double kPi = 3.14159265358979323846;
    auto bin = [](double x, double y, double z) {
        const int iz = std::min(kZ - 1, int((z + 1) * 0.5 * kZ));
        const double phi = std::atan2(y, x) + kPi;
        return iz * kPhi + std::min(kPhi - 1, int(phi / (2 * kPi) * kPhi));
    };
    std::vector<double> observed(kZ * kPhi, 0.0), expected(kZ * kPhi, 0.0);
    for (int i = 0; i < draws; ++i) {
        const auto d = draw();
        observed[size_t(bin(d.x, d.y, d.z))] += 1;
    }
    SphereChiSquare r;
    const double cell = (2.0 / kZ) * (2 * kPi / kPhi) / (kSub * kSub);  // sr per sub-cell
    for (int iz = 0; iz < kZ * kSub; ++iz)
        for (int ip = 0; ip < kPhi * kSub; ++ip) {
            const double z = -1.0 + (iz + 0.5) * 2.0 / (kZ * kSub);
            const double phi = -kPi + (ip + 0.5) * 2 * kPi / (kPhi * kSub);
            const double s = std::sqrt(std::max(0.0, 1 - z * z));
            const double p = pdf(s * std::cos(phi), s * std::sin(phi), z) * cell;
            r.integral += p;
            expected[size_t(bin(s * std::cos(phi), s * std::sin(phi), z))] += p * draws;
        }
    r.fit = chiSquare(observed, expected);
    return r;
}

}  // namespace mirage::test
