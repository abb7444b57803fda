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
//
// Surfaces: the camera ray's flight ends at the nearest surface. A diffuse surface scores its
// emission and its direct light (NEE through the media, blocked by surfaces) and ends the path:
// one bounce, as a medium event. A mirror or glass surface is followed (its BSDF sample, up to
// kMaxSpecularBounces), so the first diffuse or medium event may be seen through glass. A
// dispersive dielectric keeps the hero wavelength only, as in volpath.cpp.
#include <optional>

#include "render/direct_light.h"
#include "render/integrator.h"

namespace mirage {

namespace {

class SingleScatterIntegrator : public Integrator {
public:
    explicit SingleScatterIntegrator(bool directLight) : mDirect(directLight) {}
    std::string name() const override { return "single"; }

    // Mirror and glass vertices followed before the path gives up (a glass sphere needs 2).
    static constexpr int kMaxSpecularBounces = 16;

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        SampledSpectrum beta(1.f);
        const GeometryScene* geometry = scene.hasSurfaces() ? scene.geometry.get() : nullptr;
        bool heroOnly = false;
        Ray ray = cameraRay;
        for (int bounce = 0;; ++bounce) {
            std::optional<SurfaceHit> hit;
            if (geometry) hit = geometry->intersect(ray);
            const float tEnd = hit ? hit->t : ray.tMax;
            bool escaped = trackCollisions(ts.tracking, ray, tEnd, sampler, [&](const Collision& c) {
                const Medium& m = ts.tracking.medium(c.medium);
                if (m.emissive()) out.L += beta * c.mp.sigmaA * c.mp.Le / c.sigmaMaj;

                EventProbabilities e = eventProbabilities(c, beta);
                float u = sampler.get1D();
                if (u < e.pAbsorb) {
                    beta = SampledSpectrum(0.f);
                    return Track::Stop;
                }
                if (u < e.pAbsorb + e.pScatter) {
                    SampledSpectrum weight = beta * c.mp.sigmaS / (c.sigmaMaj * e.pScatter);
                    if (mDirect) out.L += weight * directLightMedium(scene, c, -ray.d, sampler, ts);
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
            if (bounce == 0)
                out.alpha = escaped && !hit ? clamp(1.f - beta.average(), 0.f, 1.f) : 1.f;
            if (!escaped || !hit || bounce >= kMaxSpecularBounces) break;

            // The surface: emission and direct light where it is diffuse, else follow the mirror
            // or glass.
            const Material& mat = geometry->materialAt(*hit);
            const Vec3 wo = -ray.d;
            if (mat.emissive()) out.L += beta * mat.emission(w);
            if (!mat.specular()) {
                if (mDirect) out.L += beta * directLightSurface(scene, *hit, mat, wo, sampler, ts);
                break;
            }
            Frame frame(hit->ns);
            float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
            BsdfSample bs;
            if (!mat.sample(frame.toLocal(wo), uc, u1, u2, w, TransportMode::Radiance, &bs)) break;
            beta *= bs.weight;
            if (bs.dispersed && !heroOnly) {
                heroOnly = true;
                for (int i = 1; i < kSpectrumSamples; ++i) beta[i] = 0.f;
            }
            ray = spawnRay(*hit, frame.toWorld(bs.wi));
        }
        if (heroOnly) {
            out.L[0] *= float(kSpectrumSamples);
            for (int i = 1; i < kSpectrumSamples; ++i) out.L[i] = 0.f;
        }
        return out;
    }

private:
    bool mDirect;
};

}  // namespace

std::unique_ptr<Integrator> makeSingleScatterIntegrator(bool directLight) {
    return std::make_unique<SingleScatterIntegrator>(directLight);
}

}  // namespace mirage
