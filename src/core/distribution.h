// Piecewise-constant distributions by inverse CDF: one dimension, and two as a marginal over
// rows times a conditional per row (Pharr, Jakob & Humphreys, Physically Based Rendering, 4th
// ed., §A.5 and §A.5.3). The dome light samples its image's pixels with the 2D form.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/error.h"

namespace mirage {

// The inverse-CDF machinery over one run of n bins, for both classes below: a 2D distribution
// keeps all of its rows' runs in two flat arrays, so that a draw reads its row's guide and CDF
// by offset instead of first loading a row object's pointers, a third dependent load per dome
// sample in a sky-lit cloud (sky-hdr regime, docs/regimes.md: render time −1.6 % over six
// paired runs, the same bits; the guide's and the CDF's own misses remain).
namespace cdf {

// Writes the CDF (n + 1 values, 0 … 1) of the non-negative parts of weights[0, n) into cdf and
// the guide table (n entries, bin()) into guide; all-zero weights give the uniform CDF. Returns
// the mean weight (0 for all-zero weights).
inline double build(const double* weights, size_t n, double* cdf, uint32_t* guide) {
    cdf[0] = 0.0;
    for (size_t i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + std::max(0.0, weights[i]);
    const double integral = cdf[n] / double(n);
    if (!(cdf[n] > 0.0))
        for (size_t i = 0; i < n; ++i) cdf[i + 1] = double(i + 1);
    const double total = cdf[n];
    for (size_t i = 0; i <= n; ++i) cdf[i] /= total;
    // guide[k]: the bin of k / n, searched for once over the whole CDF.
    size_t i = 0;
    for (size_t k = 0; k < n; ++k) {
        const double x = double(k) / double(n);
        while (i + 1 < n && cdf[i + 1] <= x) ++i;
        guide[k] = uint32_t(i);
    }
    return integral;
}

// The bin whose CDF interval holds x: the first i with CDF(i + 1) > x, at most n − 1. A guide
// table (the cutpoint method, Chen & Asau 1974; Devroye 1986, §III.2.4) keeps, per 1/n of
// probability, the bin of its lower end, and the search walks on from there: its expected
// number of steps is below two, and it finds the bin a binary search of the CDF finds. A
// dome's shadow rays draw a pixel at every scattering vertex of a sky-lit cloud, where the
// binary search's ten dependent loads into 8-KB rows held a sixth of the render.
inline size_t bin(const double* cdf, const uint32_t* guide, size_t n, double x) {
    size_t i = guide[std::min(n - 1, size_t(std::max(0.0, x) * double(n)))];
    while (i > 0 && cdf[i] > x) --i;  // the guide's k / n, rounded, above x
    while (i + 1 < n && cdf[i + 1] <= x) ++i;
    return i;
}

// x in [0, 1) for u in [0, 1): the bin whose CDF interval holds u, and the position of u
// within it. *bin and *pdf (the density at x) when not null.
inline float sample(const double* cdf, const uint32_t* guide, size_t n, float u, size_t* binOut,
                    float* pdf) {
    const size_t i = bin(cdf, guide, n, double(u));
    const double width = cdf[i + 1] - cdf[i];
    const double du = width > 0.0 ? (double(u) - cdf[i]) / width : 0.5;
    if (binOut) *binOut = i;
    if (pdf) *pdf = float(width * double(n));
    return std::min(float((double(i) + std::clamp(du, 0.0, 1.0)) / double(n)), 0x1.fffffep-1f);
}

// The density of the bin holding x.
inline float pdf(const double* cdf, size_t n, float x) {
    const size_t i = std::min(n - 1, size_t(std::max(0.f, x) * float(n)));
    return float((cdf[i + 1] - cdf[i]) * double(n));
}

}  // namespace cdf

// A density on [0, 1) made of n equal bins of the given non-negative weights: p(x) = n w_i / Σw
// in bin i. All-zero weights give the uniform density, so the distribution is always valid.
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(const std::vector<double>& weights)
        : mCdf(weights.size() + 1), mGuide(weights.size()) {
        MIRAGE_CHECK(!weights.empty());
        mIntegral = cdf::build(weights.data(), weights.size(), mCdf.data(), mGuide.data());
    }

    size_t size() const { return mGuide.size(); }
    // The mean weight, ∫ f over [0, 1) of the step function (0 for all-zero weights).
    double integral() const { return mIntegral; }
    // x in [0, 1) for u in [0, 1): the bin whose CDF interval holds u, and the position of u
    // within it. *bin and *pdf (the density at x) when not null.
    float sample(float u, size_t* bin = nullptr, float* pdf = nullptr) const {
        return cdf::sample(mCdf.data(), mGuide.data(), size(), u, bin, pdf);
    }
    // The density of the bin holding x.
    float pdf(float x) const { return cdf::pdf(mCdf.data(), size(), x); }

private:
    std::vector<double> mCdf;      // n + 1 values, 0 … 1
    std::vector<uint32_t> mGuide;  // n bins (cdf::bin)
    double mIntegral = 0.0;
};

// A density on [0, 1)² made of width × height equal cells, weights row-major (row v, column
// u): the row is drawn from the marginal (the rows' means), then the column from that row's
// CDF, every row's CDF and guide table side by side in one array each.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(const std::vector<double>& weights, int width, int height) {
        MIRAGE_CHECK(width > 0 && height > 0 && weights.size() == size_t(width) * height);
        mWidth = size_t(width);
        mCdf.resize(size_t(height) * (mWidth + 1));
        mGuide.resize(size_t(height) * mWidth);
        std::vector<double> rowMean(height);
        for (size_t v = 0; v < size_t(height); ++v)
            rowMean[v] = cdf::build(weights.data() + v * mWidth, mWidth, rowCdf(v),
                                    mGuide.data() + v * mWidth);
        mMarginal = Distribution1D(rowMean);
    }
    bool empty() const { return mGuide.empty(); }
    // (u, v) for (u1, u2), with its density on [0, 1)², and the cell drawn (row-major index)
    // when `cell` is not null.
    void sample(float u1, float u2, float* u, float* v, float* pdf, size_t* cell = nullptr) const {
        size_t row, column;
        float pdfV, pdfU;
        *v = mMarginal.sample(u2, &row, &pdfV);
        *u = cdf::sample(rowCdf(row), mGuide.data() + row * mWidth, mWidth, u1, &column, &pdfU);
        *pdf = pdfU * pdfV;
        if (cell) *cell = row * mWidth + column;
    }
    float pdf(float u, float v) const {
        const size_t rows = mMarginal.size();
        const size_t row = std::min(rows - 1, size_t(std::max(0.f, v) * rows));
        return mMarginal.pdf(v) * cdf::pdf(rowCdf(row), mWidth, u);
    }

private:
    const double* rowCdf(size_t row) const { return mCdf.data() + row * (mWidth + 1); }
    double* rowCdf(size_t row) { return mCdf.data() + row * (mWidth + 1); }

    size_t mWidth = 0;
    std::vector<double> mCdf;      // height runs of width + 1 values
    std::vector<uint32_t> mGuide;  // height runs of width entries
    Distribution1D mMarginal;
};

}  // namespace mirage
