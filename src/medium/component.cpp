#include "medium/component.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mirage {

namespace {

// σ = C · σ(λ): smoke, fog, pure sea water, CDOM.
class LinearComponent : public ComponentModel {
public:
    explicit LinearComponent(const MediumComponent& c)
        : ComponentModel(true),
          mSigmaA(c.sigmaA),
          mSigmaS(c.sigmaS),
          mMaxSigmaA(c.sigmaA.maxValue()),
          mMaxSigmaS(c.sigmaS.maxValue()) {}

    bool grey() const override { return mSigmaA.isConstant() && mSigmaS.isConstant(); }
    float sigmaA(float C, float lambdaNm) const override { return C * mSigmaA(lambdaNm); }
    float sigmaS(float C, float lambdaNm) const override { return C * mSigmaS(lambdaNm); }
    void sigmaADense(float C, float* out) const override {
        for (int i = 0; i < Spectrum::kDenseSamples; ++i)
            out[i] = C * mSigmaA(kLambdaMin + float(i));
    }

    // σt ≤ C · (max σa + max σs): the two maxima may sit at different wavelengths.
    double sigmaTBound(double C) const override { return C * (double(mMaxSigmaA) + mMaxSigmaS); }
    void addToMajorant(MajorantGrid* majorant, const FloatGrid* grid, float k) const override {
        const float scale = k * (mMaxSigmaA + mMaxSigmaS);
        if (grid)
            majorant->addGrid(*grid, scale);
        else
            majorant->addConstant(scale);
    }

    void sampleWavelengths(const SampledWavelengths& w, float k,
                           PathCoefficients* out) const override {
        out->sigmaA = mSigmaA.sample(w) * k;
        out->sigmaS = mSigmaS.sample(w) * k;
    }

    // τ(λ) = σt(λ) ∫ C ds.
    std::vector<float> depthPowers() const override { return {1.f}; }
    float opticalDepth(float lambdaNm, const DepthIntegrals& integrals) const override {
        return (mSigmaA(lambdaNm) + mSigmaS(lambdaNm)) * integrals[0];
    }

protected:
    void evalLaw(const PathCoefficients& pc, float v, SampledSpectrum* sigmaA,
                 SampledSpectrum* sigmaS) const override {
        evalLinear(pc, v, sigmaA, sigmaS);
    }

private:
    Spectrum mSigmaA, mSigmaS;
    float mMaxSigmaA, mMaxSigmaS;
};

// Upper bound over all wavelengths of σt of a power-law component at concentration C:
// σa(λ) = A(λ) C^e(λ) and σs(λ) = b(λ) C^s with A, e, b linear between whole nanometres (the
// dense form of Spectrum). Within one such interval C^e is monotone in λ, so its maximum is at
// an end, and the product is bounded by the larger A times the larger C^e of the two ends.
class PowerLawBound {
public:
    explicit PowerLawBound(const MediumComponent& c)
        : mSigmaSMax(c.sigmaS.maxValue()), mExponentS(c.sigmaSExponent) {
        for (int i = 0; i + 1 < Spectrum::kDenseSamples; ++i) {
            float l0 = kLambdaMin + float(i), l1 = l0 + 1.f;
            float e0 = c.sigmaAExponent(l0), e1 = c.sigmaAExponent(l1);
            mIntervals.push_back(
                {std::max(c.sigmaA(l0), c.sigmaA(l1)), std::min(e0, e1), std::max(e0, e1)});
        }
    }
    // Non-decreasing in C (every exponent is ≥ 0). The relative margin covers float exp/log.
    float operator()(float C) const {
        if (!(C > 0.f)) return 0.f;
        double lc = std::log(double(C)), m = 0.0;
        for (const Interval& iv : mIntervals)
            m = std::max(m, iv.aMax * std::exp((lc >= 0.0 ? iv.eMax : iv.eMin) * lc));
        return float((m + mSigmaSMax * std::exp(mExponentS * lc)) * (1.0 + 1e-4));
    }

private:
    struct Interval {
        double aMax, eMin, eMax;
    };
    std::vector<Interval> mIntervals;
    double mSigmaSMax, mExponentS;
};

// PowerLawBound on the grid values of a majorant's cells, through a table at geometrically
// spaced concentrations (ratio 10^(4/255) ≈ 1.037) from 1e-4 × the largest to the largest: a
// cell gets the bound at the next tabulated C above its own, which is ≥ its bound because the
// bound grows with C. 256 × 470 exponentials instead of one PowerLawBound per cell.
class TabulatedBound {
public:
    TabulatedBound(const PowerLawBound& f, float cMax) : mF(f) {
        mC0 = cMax * 1e-4f;
        mLogStep = std::log(1e4) / (kSize - 1);
        for (int k = 0; k < kSize; ++k) {
            mC[k] = float(mC0 * std::exp(k * mLogStep));
            mValue[k] = f(mC[k]);
        }
        mC[kSize - 1] = cMax;
        mValue[kSize - 1] = f(cMax);
    }
    float operator()(float C) const {
        if (!(C > 0.f)) return 0.f;
        if (!(mC0 > 0.0)) return mF(C);  // an empty grid: no table
        int k = C <= mC0 ? 0 : int(std::ceil(std::log(double(C) / mC0) / mLogStep));
        k = std::max(k - 1, 0);
        while (k < kSize && mC[k] < C) ++k;  // the first tabulated C ≥ C, despite rounding
        return k < kSize ? mValue[k] : mF(C);
    }

private:
    static constexpr int kSize = 256;
    const PowerLawBound& mF;
    double mC0, mLogStep;
    std::array<float, kSize> mC, mValue;
};

// σa = A(λ) C^e(λ), σs = b(λ) C^s: phytoplankton (chlorophyll). Every exponent is ≥ 0, so σ
// grows with C and a cell's largest C bounds it.
class PowerLawComponent : public ComponentModel {
public:
    explicit PowerLawComponent(const MediumComponent& c)
        : ComponentModel(false),
          mA(c.sigmaA),
          mB(c.sigmaS),
          mExponentA(c.sigmaAExponent),
          mExponentS(c.sigmaSExponent),
          mBound(c) {
        // Optical depth: the exponents e_m = eLo + m·de, de ≤ kExponentStep, spanning e(λ).
        float eLo = kInfinity, eHi = -kInfinity;
        for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
            float e = mExponentA(kLambdaMin + float(i));
            eLo = std::min(eLo, e);
            eHi = std::max(eHi, e);
        }
        mELo = eLo;
        mCount = std::max(2, int(std::ceil((eHi - eLo) / kExponentStep)) + 1);
        mDe = (eHi - eLo) / float(mCount - 1);
        if (!(mDe > 0.f)) mDe = 1.f;  // a constant exponent: both integrals hold the same
    }

    bool grey() const override { return false; }
    float sigmaA(float C, float lambdaNm) const override {
        return C > 0.f ? mA(lambdaNm) * std::pow(C, mExponentA(lambdaNm)) : 0.f;
    }
    float sigmaS(float C, float lambdaNm) const override {
        return C > 0.f ? mB(lambdaNm) * std::pow(C, mExponentS) : 0.f;
    }
    // C^e = exp(e ln C): one logarithm for every wavelength.
    void sigmaADense(float C, float* out) const override {
        const float lc = C > 0.f ? std::log(C) : 0.f;
        for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
            const float l = kLambdaMin + float(i);
            out[i] = C > 0.f ? mA(l) * std::exp(mExponentA(l) * lc) : 0.f;
        }
    }

    double sigmaTBound(double C) const override { return double(mBound(float(std::min(C, 3e38)))); }
    void addToMajorant(MajorantGrid* majorant, const FloatGrid* grid, float k) const override {
        if (!grid) {
            majorant->addConstant(mBound(k));
            return;
        }
        TabulatedBound table(mBound, k * grid->maxValue());
        majorant->addGridMonotone(*grid, [&](float v) { return table(k * v); });
    }

    void sampleWavelengths(const SampledWavelengths& w, float k,
                           PathCoefficients* out) const override {
        out->sigmaA = mA.sample(w);
        out->sigmaS = mB.sample(w);
        out->exponentA = mExponentA.sample(w);
        out->scale = k;
    }

    // The integrals of C^e_m for the exponents e_m spaced ≤ 0.02 apart over the range of e(λ),
    // then of C^s. At a wavelength, ∫ C^e(λ) ds is interpolated linearly in e between the two
    // nearest e_m. ∫ C^e ds is smooth in e (d²/de² = ∫ C^e ln²C ds), so the relative error is
    // ≤ (0.02)²/8 · max ln²C: below 0.05 % for C within 0.05–20 mg/m³ of the grid's unit.
    std::vector<float> depthPowers() const override {
        std::vector<float> powers;
        for (int m = 0; m < mCount; ++m) powers.push_back(mELo + float(m) * mDe);
        powers.push_back(mExponentS);
        return powers;
    }
    float opticalDepth(float lambdaNm, const DepthIntegrals& integrals) const override {
        float x = clamp((mExponentA(lambdaNm) - mELo) / mDe, 0.f, float(mCount - 1));
        int m = std::min(int(x), mCount - 2);
        float w = x - float(m);
        float integral = (1.f - w) * integrals[m] + w * integrals[m + 1];
        return mA(lambdaNm) * integral + mB(lambdaNm) * integrals[mCount];
    }

protected:
    // C^e = exp(e ln C): one logarithm for the path's wavelengths and both coefficients.
    void evalLaw(const PathCoefficients& pc, float v, SampledSpectrum* sigmaA,
                 SampledSpectrum* sigmaS) const override {
        float C = pc.scale * v;
        if (!(C > 0.f)) {
            *sigmaS = SampledSpectrum(0.f);
            return;
        }
        float lc = std::log(C);
        for (int j = 0; j < kSpectrumSamples; ++j)
            (*sigmaA)[j] += pc.sigmaA[j] * std::exp(pc.exponentA[j] * lc);
        *sigmaS = pc.sigmaS * std::exp(mExponentS * lc);
    }

private:
    static constexpr float kExponentStep = 0.02f;
    Spectrum mA, mB, mExponentA;
    float mExponentS;
    PowerLawBound mBound;
    float mELo, mDe;
    int mCount;
};

}  // namespace

std::shared_ptr<const ComponentModel> ComponentModel::make(const MediumComponent& c) {
    switch (c.kind) {
        case ComponentKind::Linear:
        case ComponentKind::Water:
        case ComponentKind::Cdom:
            return std::make_shared<LinearComponent>(c);
        case ComponentKind::Chlorophyll:
            return std::make_shared<PowerLawComponent>(c);
    }
    return std::make_shared<LinearComponent>(c);
}

}  // namespace mirage
