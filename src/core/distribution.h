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

// A density on [0, 1) made of n equal bins of the given non-negative weights: p(x) = n w_i / Σw
// in bin i. All-zero weights give the uniform density, so the distribution is always valid.
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(std::vector<double> weights) : mWeight(std::move(weights)) {
        MIRAGE_CHECK(!mWeight.empty());
        mCdf.assign(mWeight.size() + 1, 0.0);
        for (size_t i = 0; i < mWeight.size(); ++i) {
            mWeight[i] = std::max(0.0, mWeight[i]);
            mCdf[i + 1] = mCdf[i] + mWeight[i];
        }
        mIntegral = mCdf.back() / double(mWeight.size());
        if (!(mCdf.back() > 0.0)) {
            std::fill(mWeight.begin(), mWeight.end(), 1.0);
            for (size_t i = 0; i < mWeight.size(); ++i) mCdf[i + 1] = double(i + 1);
        }
        for (double& c : mCdf) c /= mCdf.back();
        buildGuide();
    }

    size_t size() const { return mWeight.size(); }
    // The mean weight, ∫ f over [0, 1) of the step function (0 for all-zero weights).
    double integral() const { return mIntegral; }
    // x in [0, 1) for u in [0, 1): the bin whose CDF interval holds u, and the position of u
    // within it. *bin and *pdf (the density at x) when not null.
    float sample(float u, size_t* bin = nullptr, float* pdf = nullptr) const {
        const size_t n = mWeight.size();
        const size_t i = binOf(double(u));
        const double width = mCdf[i + 1] - mCdf[i];
        const double du = width > 0.0 ? (double(u) - mCdf[i]) / width : 0.5;
        if (bin) *bin = i;
        if (pdf) *pdf = float(width * double(n));
        return std::min(float((double(i) + std::clamp(du, 0.0, 1.0)) / double(n)), 0x1.fffffep-1f);
    }
    // The density of the bin holding x.
    float pdf(float x) const {
        const size_t n = mWeight.size();
        const size_t i = std::min(n - 1, size_t(std::max(0.f, x) * float(n)));
        return float((mCdf[i + 1] - mCdf[i]) * double(n));
    }

private:
    // The bin whose CDF interval holds x: the first i with CDF(i + 1) > x, at most n − 1. A guide
    // table (the cutpoint method, Chen & Asau 1974; Devroye 1986, §III.2.4) keeps, per 1/n of
    // probability, the bin of its lower end, and the search walks on from there: its expected
    // number of steps is below two, and it finds the bin a binary search of the CDF finds. A
    // dome's shadow rays draw a pixel at every scattering vertex of a sky-lit cloud, where the
    // binary search's ten dependent loads into 8-KB rows held a sixth of the render.
    size_t binOf(double x) const {
        const size_t n = mWeight.size();
        size_t i = mGuide[std::min(n - 1, size_t(std::max(0.0, x) * double(n)))];
        while (i > 0 && mCdf[i] > x) --i;  // the guide's k / n, rounded, above x
        while (i + 1 < n && mCdf[i + 1] <= x) ++i;
        return i;
    }
    // mGuide[k]: the bin of k / n, searched for once over the whole CDF.
    void buildGuide() {
        const size_t n = mWeight.size();
        mGuide.resize(n);
        size_t i = 0;
        for (size_t k = 0; k < n; ++k) {
            const double x = double(k) / double(n);
            while (i + 1 < n && mCdf[i + 1] <= x) ++i;
            mGuide[k] = uint32_t(i);
        }
    }

    std::vector<double> mWeight;
    std::vector<double> mCdf;  // n + 1 values, 0 … 1
    std::vector<uint32_t> mGuide;  // n bins (binOf)
    double mIntegral = 0.0;
};

// A density on [0, 1)² made of width × height equal cells, weights row-major (row v, column
// u): the row is drawn from the marginal (the rows' sums), then the column from that row.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(const std::vector<double>& weights, int width, int height) {
        MIRAGE_CHECK(width > 0 && height > 0 && weights.size() == size_t(width) * height);
        std::vector<double> rowSum(height);
        for (int v = 0; v < height; ++v) {
            auto first = weights.begin() + ptrdiff_t(v) * width;
            mRows.emplace_back(std::vector<double>(first, first + width));
            rowSum[v] = mRows.back().integral();
        }
        mMarginal = Distribution1D(std::move(rowSum));
    }
    bool empty() const { return mRows.empty(); }
    // (u, v) for (u1, u2), with its density on [0, 1)², and the cell drawn (row-major index)
    // when `cell` is not null.
    void sample(float u1, float u2, float* u, float* v, float* pdf, size_t* cell = nullptr) const {
        size_t row, column;
        float pdfV, pdfU;
        *v = mMarginal.sample(u2, &row, &pdfV);
        *u = mRows[row].sample(u1, &column, &pdfU);
        *pdf = pdfU * pdfV;
        if (cell) *cell = row * mRows[row].size() + column;
    }
    float pdf(float u, float v) const {
        const size_t row = std::min(mRows.size() - 1, size_t(std::max(0.f, v) * mRows.size()));
        return mMarginal.pdf(v) * mRows[row].pdf(u);
    }

private:
    std::vector<Distribution1D> mRows;
    Distribution1D mMarginal;
};

}  // namespace mirage
