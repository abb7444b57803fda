// Fluorescence in the photon walk (Gutierrez et al. 2005): in a homogeneous medium whose one
// absorber has quantum efficiency Γ, the fraction of absorptions that re-emit is Γ (binomial,
// 3σ), the re-emitted wavelengths follow the emission band η (χ²), no re-emission raises a
// photon's energy (λo ≥ λi, power × λi/λo ≤ power), and Γ = 0 walks bit for bit as a shader
// without fluorescence.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "unit/chi_square.h"
#include "medium/fluorescence.h"
#include "photon/photon_walk.h"

using namespace mirage;

namespace {

constexpr float kGamma = 0.3f;

// σa = 1/m (fluorescent with Γ), σs = 1/m isotropic, filling a box ±1 km: no photon leaves.
std::unique_ptr<Medium> fluorescentMedium(float gamma, bool declareBand = true) {
    ShaderDesc s;
    s.name = "fluorescent";
    MediumComponent c;
    c.sigmaA = Spectrum(1.f);
    c.sigmaS = Spectrum(1.f);
    if (declareBand) {
        c.quantumEfficiency = gamma;
        c.emissionPeakNm = 685.f;
        c.emissionFwhmNm = 25.f;
    }
    s.components.push_back(c);
    Bounds3 box;
    box.expand(Vec3(-1000.f));
    box.expand(Vec3(1000.f));
    return std::make_unique<Medium>(s, box, Transform(), 1.f);
}

struct WalkResult {
    FlightEnd firstEnd = FlightEnd::Escaped;  // how the first absorption event ended
    float firstLambdaOut = 0.f;
    std::vector<FlightEvent> events;  // every event until the photon is absorbed for good
};

WalkResult walkPhoton(PhotonWalk& walk, uint64_t index, float lambda, int maxEvents = 1000) {
    WalkResult r;
    Sampler s(41, index, 0);
    walk.setWavelength(lambda);
    Ray ray{Vec3(0.f), Vec3(0.f, 0.f, 1.f), kInfinity};
    for (int i = 0; i < maxEvents; ++i) {
        FlightEvent ev = walk.fly(ray, kInfinity, s);
        r.events.push_back(ev);
        if (ev.end != FlightEnd::Scattered && r.firstEnd == FlightEnd::Escaped) {
            r.firstEnd = ev.end;
            r.firstLambdaOut = walk.wavelength();
        }
        if (ev.end == FlightEnd::Absorbed || ev.end == FlightEnd::Escaped) break;
        ray = Ray{ev.p, ev.wo, kInfinity};
    }
    return r;
}

}  // namespace

TEST(FluorescenceWalk, ReemittedOverAbsorbedIsGammaAndFollowsEta) {
    auto m = fluorescentMedium(kGamma);
    PhotonWalk walk({m.get()});
    const int n = 200000, bins = 120;
    const float lo = 620.f;  // histogram of λo over [620, 740) nm
    int absorbed = 0, reemitted = 0;
    std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
    for (int i = 0; i < n; ++i) {
        // The photon's first absorption, at 450 nm, where the whole band is allowed.
        WalkResult r = walkPhoton(walk, uint64_t(i), 450.f);
        ASSERT_NE(r.firstEnd, FlightEnd::Escaped);
        ++absorbed;
        if (r.firstEnd != FlightEnd::Reemitted) continue;
        ++reemitted;
        int b = int(std::floor(r.firstLambdaOut - lo));
        if (b >= 0 && b < bins) observed[size_t(b)] += 1;
    }
    double ratio = double(reemitted) / absorbed;
    double sigma = std::sqrt(kGamma * (1 - kGamma) / absorbed);
    EXPECT_NEAR(ratio, kGamma, 3 * sigma);
    std::printf("re-emitted / absorbed = %.5f, Γ = %.2f, σ = %.5f\n", ratio, kGamma, sigma);

    // η: the Gaussian band, piecewise linear between whole nm (its dense form), normalised.
    Spectrum band = gaussianBand(685.f, 25.f);
    double total = 0.0;
    for (float l = kLambdaMin; l < kLambdaMax; l += 1.f) total += 0.5 * (band(l) + band(l + 1));
    for (int b = 0; b < bins; ++b)
        expected[size_t(b)] = reemitted * 0.5 * (band(lo + b) + band(lo + b + 1)) / total;
    auto chi = test::chiSquare(observed, expected);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof)) << "dof " << chi.dof;
}

TEST(FluorescenceWalk, EnergyIsNeverCreated) {
    auto m = fluorescentMedium(0.9f);
    PhotonWalk walk({m.get()});
    int reemissions = 0;
    for (int i = 0; i < 20000; ++i) {
        // Photons absorbed anywhere in the spectrum, re-emitted again and again (Γ = 0.9).
        WalkResult r = walkPhoton(walk, uint64_t(i), 400.f + 0.02f * float(i));
        for (const FlightEvent& ev : r.events) {
            if (ev.end != FlightEnd::Reemitted) continue;
            ++reemissions;
            ASSERT_GE(ev.lambdaOut, ev.lambdaIn);
            ASSERT_LE(ev.weight, 1.f);
            ASSERT_NEAR(ev.weight, ev.lambdaIn / ev.lambdaOut, 1e-6f);
        }
    }
    EXPECT_GT(reemissions, 10000);
}

TEST(FluorescenceWalk, GammaZeroIsBitIdenticalToNoFluorescence) {
    auto zero = fluorescentMedium(0.f), plain = fluorescentMedium(0.f, false);
    PhotonWalk a({zero.get()}), b({plain.get()});
    for (int i = 0; i < 2000; ++i) {
        WalkResult ra = walkPhoton(a, uint64_t(i), 550.f), rb = walkPhoton(b, uint64_t(i), 550.f);
        ASSERT_EQ(ra.events.size(), rb.events.size());
        for (size_t k = 0; k < ra.events.size(); ++k) {
            ASSERT_EQ(ra.events[k].end, rb.events[k].end);
            ASSERT_EQ(ra.events[k].p.x, rb.events[k].p.x);
            ASSERT_EQ(ra.events[k].p.z, rb.events[k].p.z);
            ASSERT_EQ(ra.events[k].wo.y, rb.events[k].wo.y);
        }
    }
}
