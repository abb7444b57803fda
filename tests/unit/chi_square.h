// Pearson's χ² goodness-of-fit test for the sampling tests (every sampling routine gets one,
// STYLE.md): observed histogram counts against the counts its density predicts.
#pragma once

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

}  // namespace mirage::test
