// The weight a camera path gives the photons it gathers, as a function of each photon's
// wavelength.
//
// A photon estimate sums photons at their own wavelengths λp, none of which is one of the
// camera path's four, so every factor the camera path puts in front of a segment must be known
// at any λ: the transmittance of the media crossed before it (earlier chords of a curved
// camera ray, earlier segments of a specular chain), the reflectance of a tinted mirror. Grey
// factors are one number; the others are tabulated from 360 to 830 nm every 5 nm and
// interpolated linearly, which reproduces the smooth spectra of media and materials to well
// within the photon estimate's own noise.
//
// Behind a dispersive refraction the camera path follows the direction of its hero wavelength
// λh alone (material.h), so it may gather only light of that wavelength. The photons near λh
// stand for it: W(λp) = k(λp − λh) / p(λh), a tent kernel k of half-width kHeroBandwidth
// (∫ k = 1) over the wavelength pdf p of the hero sample. Its expectation over λh is the
// XYZ of the light smoothed over ±kHeroBandwidth in wavelength, a bias like the estimate's
// spatial blur and of the same order as the interpolation above: it softens the colours of a
// prism's fringes by a 10 nm blur, far finer than the fringes themselves.
#pragma once

#include <array>

#include "core/math.h"

namespace mirage {

class ViewWeight {
public:
    static constexpr float kLambdaMin = 360.f, kLambdaMax = 830.f, kStep = 5.f;
    static constexpr int kCount = 95;  // (830 − 360) / 5 + 1
    static constexpr float kHeroBandwidth = 10.f;  // nm, half-width of the tent

    // A grey factor.
    void scale(float s) { mScale *= s; }
    // A factor f(λ) that varies with wavelength (f: float(float lambdaNm)).
    template <typename F>
    void multiply(F&& f) {
        if (!mTabulated) {
            mTable.fill(1.f);
            mTabulated = true;
        }
        for (int j = 0; j < kCount; ++j) mTable[size_t(j)] *= f(kLambdaMin + kStep * float(j));
    }
    // From here on only light of the hero wavelength (pdf: its sampling density, 1/nm) counts.
    void keepHero(float lambdaNm, float pdf) {
        if (mHero) return;  // the first dispersive vertex chose the path's wavelength
        mHero = true;
        mHeroLambda = lambdaNm;
        mScale /= pdf;
    }

    bool zero() const { return !(mScale > 0.f); }
    bool one() const { return mScale == 1.f && !mTabulated && !mHero; }

    float operator()(float lambdaNm) const {
        float w = mScale;
        if (mHero) {
            const float d = std::abs(lambdaNm - mHeroLambda);
            if (!(d < kHeroBandwidth)) return 0.f;
            w *= (1.f - d / kHeroBandwidth) / kHeroBandwidth;
        }
        if (mTabulated) {
            const float x = clamp((lambdaNm - kLambdaMin) / kStep, 0.f, float(kCount - 1));
            const int j = std::min(int(x), kCount - 2);
            const float f = x - float(j);
            w *= mTable[size_t(j)] * (1.f - f) + mTable[size_t(j) + 1] * f;
        }
        return w;
    }

private:
    float mScale = 1.f;
    bool mTabulated = false;
    std::array<float, kCount> mTable{};
    bool mHero = false;
    float mHeroLambda = 0.f;
};

}  // namespace mirage
