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
//
// Surfaces: each free flight ends at the nearest surface (tracking over (0, t_hit)). There the
// path scores the surface's emission (Lambertian emitters are found by rays only, never by
// NEE), then, on a diffuse surface, NEE to the lights, and continues along a BSDF sample:
//   surface       β ← β f |cos θi| / pdf  (ρ for Lambertian; 1 or 1/η² for glass, mirror ρ)
// A dispersive dielectric leaves only the hero wavelength alive (material.h): its other three
// throughputs become 0 and, at the end, L[0] is weighted by 4 — the estimate of a path that
// drew one wavelength from p(λ) instead of four stratified ones.
//
// Fluorescence: a path carries the wavelength light *leaves* with, so at an absorption event of
// a fluorescent medium it asks where that light could have come from: sampleInelasticAdjoint
// (transport/reemission.h) draws a component, its Γ roulette, a shorter λi and an isotropic
// direction, and returns w = n_f σa,c(λi) η(λi → λo) (λi/λo) / q(λi) — λi/λo because η counts
// photons and radiance counts energy, the adjoint of the photon walk's power × λi/λo (Mobley
// 1994 §5.13). The absorption branch was chosen
// with density σ̄ P_a, so
//   fluorescence  β₀ ← β₀ w / (σ̄ P_a),  β₁…₃ ← 0 (hero only, as dispersion), path goes on at λi
// with next-event estimation through the isotropic lobe (render/inelastic_light.h). Needs
// σa(λo) > 0 wherever σa(λi) Γ η(λi → λo) > 0, else that light is never sampled: true of water.
#include <atomic>
#include <optional>

#include "render/direct_light.h"
#include "render/inelastic_light.h"
#include "render/integrator.h"
#include "transport/reemission.h"

namespace mirage {

namespace {

class VolPathIntegrator : public Integrator {
public:
    explicit VolPathIntegrator(int maxDepth) : mMaxDepth(maxDepth) {}
    std::string name() const override { return "volpath"; }

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        SampledSpectrum beta(1.f);
        Ray ray = cameraRay;
        const GeometryScene* geometry = scene.hasSurfaces() ? scene.geometry.get() : nullptr;
        bool heroOnly = false;
        float lambdaIn = 0.f;  // > 0: the path fluoresced at this collision and goes on at λi
        bool fluoresced = false;
        for (int depth = 0;; ++depth) {
            bool scattered = false;
            Ray next;
            std::optional<SurfaceHit> hit;
            if (geometry) hit = geometry->intersect(ray);
            const float tEnd = hit ? hit->t : ray.tMax;
            bool escaped = trackCollisions(ts.tracking, ray, tEnd, sampler, [&](const Collision& c) {
                const Medium& m = ts.tracking.medium(c.medium);
                if (m.emissive()) out.L += beta * c.mp.sigmaA * c.mp.Le / c.sigmaMaj;

                EventProbabilities e = eventProbabilities(c, beta);
                float u = sampler.get1D();
                if (u < e.pAbsorb) {
                    InelasticAdjoint in;
                    if (sampleInelasticAdjoint(m, ts.tracking.context(size_t(c.medium)), c.p,
                                               ts.tracking.wavelengths().lambda[0], sampler,
                                               &in)) {
                        float hero = beta[0] * in.weight / (c.sigmaMaj * e.pAbsorb);
                        beta = SampledSpectrum(0.f);
                        beta[0] = hero;
                        heroOnly = true;
                        if (!(hero > 0.f)) return Track::Stop;
                        lambdaIn = in.lambdaInNm;
                        next = Ray{c.p, in.wi, kInfinity};
                        scattered = true;
                        return Track::Stop;
                    }
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
            if (depth == 0)
                out.alpha = escaped && !hit ? clamp(1.f - beta.average(), 0.f, 1.f) : 1.f;
            if (lambdaIn > 0.f) {
                SampledWavelengths li = ts.tracking.wavelengths();
                li.lambda.fill(lambdaIn);
                ts.tracking.setWavelengths(li);
                out.L += beta * directLightIsotropic(scene, next.o, sampler, ts);
                lambdaIn = 0.f;
                fluoresced = true;
            }
            if (!scattered && escaped && hit)
                scattered = scatterAtSurface(scene, *hit, ray, ts.tracking.wavelengths(), sampler,
                                             ts, &beta, &out.L, &heroOnly, &next);
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
        if (fluoresced) ts.tracking.setWavelengths(w);  // the caller's, for its next path
        if (heroOnly) {
            out.L[0] *= float(kSpectrumSamples);
            for (int i = 1; i < kSpectrumSamples; ++i) out.L[i] = 0.f;
        }
        return out;
    }

    uint64_t cappedPaths() const override { return mCapped.load(); }

    // The surface vertex: emission, NEE on diffuse surfaces, then the BSDF sample that
    // continues the path. Returns false when the path ends here.
    static bool scatterAtSurface(const RenderScene& scene, const SurfaceHit& hit, const Ray& ray,
                                 const SampledWavelengths& w, Sampler& sampler, ThreadState& ts,
                                 SampledSpectrum* beta, SampledSpectrum* L, bool* heroOnly,
                                 Ray* next) {
        const Material& mat = scene.geometry->materialAt(hit);
        const Vec3 wo = -ray.d;
        if (mat.emissive()) *L += *beta * mat.emission(w);
        if (!mat.specular()) *L += *beta * directLightSurface(scene, hit, mat, wo, sampler, ts);
        Frame frame(hit.ns);
        float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        BsdfSample bs;
        if (!mat.sample(frame.toLocal(wo), uc, u1, u2, w, TransportMode::Radiance, &bs))
            return false;
        Vec3 wi = frame.toWorld(bs.wi);
        // A shading normal can send a reflected sample below the geometric surface (or a
        // refracted one above it): such a sample would leak light through the surface.
        bool crosses = (dot(wi, hit.ng) > 0.f) != (dot(wo, hit.ng) > 0.f);
        if (crosses != bs.transmitted) return false;
        *beta *= bs.weight;
        if (bs.dispersed && !*heroOnly) {
            *heroOnly = true;
            for (int i = 1; i < kSpectrumSamples; ++i) (*beta)[i] = 0.f;
        }
        *next = spawnRay(hit, wi);
        return true;
    }

private:
    int mMaxDepth;
    mutable std::atomic<uint64_t> mCapped{0};
};

}  // namespace

std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth) {
    return std::make_unique<VolPathIntegrator>(maxDepth);
}

}  // namespace mirage
