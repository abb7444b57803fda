// Fluorescence in the reference path tracer: a furnace with a known answer. Inside an optically
// deep, uniform medium at temperature T whose only absorber fluoresces (Γ, Gaussian band η),
// the radiance is uniform and isotropic, and the transfer equation reduces to a balance per
// wavelength: absorption σa L(λ) = thermal emission σa Le(λ) + the inelastic source
// Γ ∫ σa η(λi → λ) (λi/λ) L(λi) dλi, i.e. the Volterra equation
//   L(λ) = Le(λ) + Γ ∫_{360}^{λ} η(λi → λ) (λi/λ) L(λi) dλi,   η(λi → λ) = η(λ) / A(λi),
// A(λi) = ∫_{λ ≥ λi} η (the Stokes rule renormalises η over λ ≥ λi). λi/λ turns the photon
// count Γ η into energy (radiance), a photon of λ carrying hc/λ (Mobley 1994, §5.13;
// transport/reemission.h); an earlier version of this reference left it out, and so did
// volpath, which then agreed with it while creating energy. It is solved here by the
// trapezoid rule at 0.05 nm, and volpath must find it: ratio 1 within its standard error.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/integrator.h"
#include "spectrum/spectrum_sampling.h"
#include "medium/fluorescence.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr float kTemperature = 4000.f;  // K
constexpr float kGamma = 0.3f, kPeak = 600.f, kFwhm = 80.f;

RenderScene fluorescentFurnace() {
    RenderScene scene;
    ShaderDesc s = test::greyShader(10.f, 10.f, 0.3f);
    s.components[0].quantumEfficiency = kGamma;
    s.components[0].emissionPeakNm = kPeak;
    s.components[0].emissionFwhmNm = kFwhm;
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    s.emission = e;
    auto one = [](int, int, int) { return 1.f; };
    auto hot = [](int, int, int) { return kTemperature; };
    Vec3d origin(-1.0, -1.0, -1.0);
    std::vector<FloatGrid> grids{test::makeGrid(one, 0, 63, 1.0 / 32, origin, "density"),
                                 test::makeGrid(hot, 0, 63, 1.0 / 32, origin, "temperature")};
    scene.media.push_back(std::make_unique<Medium>(s, std::move(grids), Transform(), 1.f, 16));
    return scene;
}

// L(λ) on a 0.05 nm grid from 360 nm, by the trapezoid rule (implicit in the last node).
class VolterraReference {
public:
    VolterraReference() {
        SpectrumSampler band(gaussianBand(kPeak, kFwhm));
        const int n = int((kLambdaMax - kLambdaMin) / kStep) + 1;
        mL.resize(size_t(n));
        double J = 0.0, prevTerm = 0.0;
        for (int k = 0; k < n; ++k) {
            double l = kLambdaMin + k * kStep;
            double le = planck(l, kTemperature) * 1e-9;
            double eta = band.pdf(float(l));
            double A = 1.0 - band.cdf(float(l));
            double invA = A > 1e-9 ? 1.0 / A : 0.0;  // as FluorescenceEmission: no band left
            double h = k > 0 ? kStep : 0.0;
            // L = Le + Γ η/λ (J + h/2 (λ_prev L_prev/A_prev + λ L/A)), J = ∫ λi L/A dλi so far,
            // solved for L (the λ of the last node cancels).
            double L = (le + kGamma * eta / l * (J + 0.5 * h * prevTerm)) /
                       (1.0 - kGamma * eta * 0.5 * h * invA);
            J += 0.5 * h * (prevTerm + l * L * invA);
            prevTerm = l * L * invA;
            mL[size_t(k)] = L;
        }
    }
    double operator()(float lambda) const {
        double x = (lambda - kLambdaMin) / kStep;
        size_t i = std::min(size_t(x), mL.size() - 2);
        double t = x - double(i);
        return mL[i] * (1 - t) + mL[i + 1] * t;
    }

private:
    static constexpr double kStep = 0.05;
    std::vector<double> mL;
};

}  // namespace

TEST(FluorescenceVolPath, FurnaceMatchesTheVolterraSolution) {
    RenderScene scene = fluorescentFurnace();
    VolterraReference ref;
    // The fluorescence is no small correction here: at the band's peak it adds over 20 % to L.
    EXPECT_GT(ref(kPeak) / (planck(kPeak, kTemperature) * 1e-9), 1.2);

    auto integrator = makeVolPathIntegrator();
    ThreadState ts(scene);
    const int n = 400000;
    double sum = 0, sum2 = 0, sumPlain = 0;
    for (int i = 0; i < n; ++i) {
        Sampler s(13, uint64_t(i), 0);
        SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        Vec3 d = sampleUniformSphere(s.get1D(), s.get1D());
        RadianceSample r = integrator->Li(scene, Ray{Vec3(0.01f, 0.02f, 0.03f), d, kInfinity}, w,
                                          s, ts);
        double ratio = 0, plain = 0;
        for (int k = 0; k < kSpectrumSamples; ++k) {
            ratio += r.L[k] / ref(w.lambda[k]) / kSpectrumSamples;
            plain += r.L[k] / (planck(w.lambda[k], kTemperature) * 1e-9) / kSpectrumSamples;
        }
        sum += ratio;
        sum2 += ratio * ratio;
        sumPlain += plain;
    }
    double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0, 4 * se + 3e-3) << "± " << se;
    // And not the non-fluorescent furnace's answer, L = Le.
    EXPECT_GT(sumPlain / n, 1.05);
    std::printf("volpath / Volterra reference = %.4f ± %.4f (L / Le = %.3f)\n", mean, se,
                sumPlain / n);
}

