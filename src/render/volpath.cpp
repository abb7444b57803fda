// The reference integrator: a spectral volumetric path tracer. It is the ground truth for
// everything the photon mapper approximates, so it makes no approximation of its own: free
// flights by delta tracking against the majorant grid (null collisions), next-event estimation
// at every real scattering event with ratio-tracked shadow rays, phase-function sampling for
// the next direction, emission scored at every tentative collision, Russian roulette on the
// throughput. Lights are reached by next-event estimation only (they are not hit by rays), so
// no multiple importance sampling is needed for the light types Mirage has.
//
// Weights (per wavelength; see transport/tracking.h):
//   emission      β σa Le / σ̄                    at every tentative collision
//   scattering    β ← β σs / (σ̄ P_s)             then NEE and β ← β p/pdf (= 1 for one lobe)
//   null          β ← β σn / (σ̄ P_n)
// A path ends by absorption (probability P_a), by leaving every medium, by roulette, or at the
// depth cap (counted in the summary: a capped path is a bias, however rare).
#include <atomic>

#include "render/direct_light.h"
#include "render/integrator.h"

namespace mirage {

namespace {

class VolPathIntegrator : public Integrator {
public:
    explicit VolPathIntegrator(int maxDepth) : mMaxDepth(maxDepth) {}
    std::string name() const override { return "volpath"; }

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths&,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        SampledSpectrum beta(1.f);
        Ray ray = cameraRay;
        for (int depth = 0;; ++depth) {
            bool scattered = false;
            Ray next;
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
                    beta *= c.mp.sigmaS / (c.sigmaMaj * e.pScatter);
                    out.L += beta * directLightMedium(scene, c, -ray.d, sampler, ts);
                    SampledSpectrum weight;
                    float pdf;
                    float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
                    Vec3 wo = m.phaseSample(c.mp, ray.d, uc, u1, u2, &weight, &pdf);
                    beta *= weight;
                    next = Ray{c.p, wo, kInfinity};
                    scattered = true;
                    return Track::Stop;
                }
                beta *= e.sigmaN / (c.sigmaMaj * e.pNull);
                return Track::Continue;
            });
            if (depth == 0) out.alpha = escaped ? clamp(1.f - beta.average(), 0.f, 1.f) : 1.f;
            if (!scattered) break;
            if (depth + 1 >= mMaxDepth) {
                mCapped.fetch_add(1, std::memory_order_relaxed);
                break;
            }
            // Russian roulette once the throughput is small (spectral media, long walks).
            float maxBeta = beta.maxValue();
            if (!(maxBeta > 0.f)) break;
            if (maxBeta < 0.25f) {
                float survive = maxBeta / 0.25f;
                if (sampler.get1D() >= survive) break;
                beta /= survive;
            }
            ray = next;
        }
        return out;
    }

    uint64_t cappedPaths() const override { return mCapped.load(); }

private:
    int mMaxDepth;
    mutable std::atomic<uint64_t> mCapped{0};
};

}  // namespace

std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth) {
    return std::make_unique<VolPathIntegrator>(maxDepth);
}

}  // namespace mirage
