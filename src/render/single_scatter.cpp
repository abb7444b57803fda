// Single scattering + emission by null-collision tracking.
//
// Along the camera ray, the radiance is L = ∫ T(t) [σa Le + σs Σ_lights ∫ p Li T_l] dt.
// Tentative collisions come at rate σ̄. At each one:
//  - emission is scored at every tentative collision, β σa Le / σ̄ (a collision estimator
//    whose expectation is ∫ T σa Le dt);
//  - then an event is chosen with the probabilities of eventProbabilities(): absorption ends
//    the path, real scattering scores β σs/(σ̄ P_s) · (direct light) and ends it (single
//    scattering), a null collision multiplies β by σn/(σ̄ P_n) and continues.
// β is 1 at every wavelength for grey media; Russian roulette keeps long spectral walks short.
// The probability of leaving the medium is T, so β at escape estimates the transmittance and
// 1 − β is the pixel's coverage (alpha).
#include "render/direct_light.h"
#include "render/integrator.h"

namespace mirage {

namespace {

class SingleScatterIntegrator : public Integrator {
public:
    std::string name() const override { return "single"; }

    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths&,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        SampledSpectrum beta(1.f);
        bool escaped = trackCollisions(ts.tracking, ray, ray.tMax, sampler, [&](const Collision& c) {
            const Medium& m = ts.tracking.medium(c.medium);
            if (m.emissive()) out.L += beta * c.mp.sigmaA * c.mp.Le / c.sigmaMaj;

            EventProbabilities e = eventProbabilities(c);
            float u = sampler.get1D();
            if (u < e.pAbsorb) {
                beta = SampledSpectrum(0.f);
                return Track::Stop;
            }
            if (u < e.pAbsorb + e.pScatter) {
                SampledSpectrum w = beta * c.mp.sigmaS / (c.sigmaMaj * e.pScatter);
                out.L += w * directLightMedium(scene, c, -ray.d, sampler, ts);
                beta = SampledSpectrum(0.f);
                return Track::Stop;
            }
            beta *= e.sigmaN / (c.sigmaMaj * e.pNull);
            float maxBeta = beta.maxValue();
            if (!(maxBeta > 0.f)) {
                beta = SampledSpectrum(0.f);
                return Track::Stop;
            }
            if (maxBeta < 0.1f) {  // Russian roulette, survival ∝ β
                float survive = maxBeta / 0.1f;
                if (sampler.get1D() >= survive) {
                    beta = SampledSpectrum(0.f);
                    return Track::Stop;
                }
                beta /= survive;
            }
            return Track::Continue;
        });
        out.alpha = escaped ? clamp(1.f - beta.average(), 0.f, 1.f) : 1.f;
        return out;
    }
};

}  // namespace

std::unique_ptr<Integrator> makeSingleScatterIntegrator() {
    return std::make_unique<SingleScatterIntegrator>();
}

}  // namespace mirage
