// The photon estimates' view weight (photon/view_weight.h): grey factors, tabulated spectra
// reproduced between their 5 nm nodes, and the hero kernel behind a dispersive vertex, whose
// expectation over the hero wavelength is 1 at every photon wavelength (the estimate of the
// light smoothed over ±10 nm), and which integrates to 1/p(λh) over photon wavelengths.
#include <gtest/gtest.h>

#include <cmath>

#include "photon/view_weight.h"

namespace mirage {
namespace {

TEST(ViewWeight, GreyAndTabulatedFactors) {
    ViewWeight w;
    EXPECT_TRUE(w.one());
    EXPECT_EQ(w(500.f), 1.f);
    w.scale(0.5f);
    EXPECT_FALSE(w.one());
    EXPECT_EQ(w(400.f), 0.5f);
    // A factor linear in λ is reproduced exactly by the linear interpolation of its nodes.
    w.multiply([](float l) { return 0.001f * l; });
    for (float l : {360.f, 401.3f, 555.5f, 829.f})
        EXPECT_NEAR(w(l), 0.5f * 0.001f * l, 1e-6f) << l;
    // A smooth transmittance, exp(−2 (λ/500)²), to 0.1 % between the nodes.
    ViewWeight t;
    auto T = [](float l) { return std::exp(-2.f * (l / 500.f) * (l / 500.f)); };
    t.multiply(T);
    for (float l = 360.f; l <= 830.f; l += 0.7f) EXPECT_NEAR(t(l), T(l), 1e-3f * T(l)) << l;
    t.scale(0.f);
    EXPECT_TRUE(t.zero());
}

TEST(ViewWeight, HeroKernelIsUnbiasedOverTheHeroWavelength) {
    // p(λh) uniform on [360, 830]: E[W(λp)] = ∫ k(λp − λh) / p · p dλh = 1 away from the ends.
    const float p = 1.f / 470.f;
    for (float lp : {400.f, 537.5f, 700.f}) {
        double mean = 0;
        const int n = 47000;
        for (int i = 0; i < n; ++i) {
            ViewWeight w;
            w.keepHero(360.f + 470.f * (float(i) + 0.5f) / float(n), p);
            mean += w(lp) / n;  // λh on a fine grid: the average over λh ~ p
        }
        EXPECT_NEAR(mean, 1.0, 1e-3) << lp;
    }
    // Over photon wavelengths the kernel integrates to 1/p(λh); the first dispersive vertex
    // chose the wavelength, a second one changes nothing.
    ViewWeight w;
    w.keepHero(550.f, 0.01f);
    w.keepHero(450.f, 0.5f);
    double integral = 0;
    for (float l = 530.f; l < 570.f; l += 0.01f) integral += w(l + 0.005f) * 0.01;
    EXPECT_NEAR(integral, 100.0, 0.1);
    EXPECT_EQ(w(560.5f), 0.f);
    EXPECT_EQ(w(450.f), 0.f);
}

}  // namespace
}  // namespace mirage
