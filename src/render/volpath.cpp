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
// Lights at infinity (the dome) are sampled by NEE like the others, so a path that leaves the
// scene scores them only where no NEE has: on the camera ray and after mirrors and glass.
//
// Surfaces: each free flight ends at the nearest surface (tracking over (0, t_hit)). There the
// path scores the surface's emission (Lambertian emitters are found by rays only, never by
// NEE), then, on a diffuse surface, NEE to the lights, and continues along a BSDF sample
// (transport/path_vertex.h: continueAtSurface):
//   surface       β ← β f |cos θi| / pdf  (ρ for Lambertian; 1 or 1/η² for glass, mirror ρ)
// A dispersive dielectric leaves only the hero wavelength alive (PathThroughput::heroOnly).
//
// Fluorescence: a path carries the wavelength light *leaves* with, so at every tentative
// collision in a fluorescent medium it first asks whether this is where that light was
// re-emitted: sampleInelasticEvent (transport/reemission.h) draws a component and chooses the
// inelastic event with a probability of its own, ∝ Γ (at least Γ P_a) — not as a branch of
// absorption, whose probability follows σa at the path's wavelengths and may be 0 at λo. Chosen:
//   fluorescence  β₀ ← β₀ w,  β₁…₃ ← 0 (hero only, as dispersion), path goes on at λi
// with w = n_f Γ σa,c(λi) η(λi → λo) (λi/λo) / (q σ̄ P_f) — λi/λo because η counts photons and
// radiance counts energy, the adjoint of the photon walk's power × λi/λo (Mobley 1994 §5.13) —
// and next-event estimation through the isotropic lobe (render/inelastic_light.h). Not chosen:
// the ordinary events, their weights divided by 1 − P_f; absorption then ends the path.
#include <atomic>
#include <cmath>

#include "render/camera_ray_data.h"
#include "render/direct_light.h"
#include "render/guided_continuation.h"
#include "render/inelastic_light.h"
#include "render/integrator.h"
#include "transport/path_vertex.h"
#include "transport/reemission.h"

namespace mirage {

namespace {

class VolPathIntegrator : public Integrator {
public:
    explicit VolPathIntegrator(int maxDepth) : mMaxDepth(maxDepth) {}
    const IntegratorInfo& info() const override { return integratorInfo("volpath"); }
    bool lightShapedRadiance() const override { return true; }

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        out.aov = ts.aov;
        out.deep = ts.deep;
        PathThroughput path;
        DeepView view;
        Ray ray = cameraRay;
        const GeometryScene* geometry = scene.hasSurfaces() ? scene.geometry.get() : nullptr;
        bool fluoresced = false;
        bool specularChain = true;  // every vertex so far a mirror or glass: escapes see the dome
        const bool guided = guidesPaths(scene);  // render/guided_continuation.h
        for (int depth = 0;; ++depth) {
            Ray next;
            std::optional<SurfaceHit> hit;
            if (geometry) hit = geometry->intersect(ray);
            const float tEnd = hit ? hit->t : ray.tMax;
            float lambdaIn = 0.f;  // > 0: the path fluoresced at this collision, goes on at λi
            bool scattered = false;
            bool heldOut = false;  // a real event in a holdout medium the camera looks into
            float eventT = 0.f;    // where the path fluoresced
            // The camera ray's walk, up to its first real collision, is the data passes' too
            // (render/camera_ray_data.h).
            CameraRayData* data = depth == 0 ? ts.cameraData : nullptr;
            const bool escaped =
                trackCollisions(ts.tracking, ray, tEnd, sampler, [&](const Collision& c) {
                    if (data) data->seen(c);
                    const Medium& m = ts.tracking.medium(c.medium);
                    // A holdout medium seen by the camera only attenuates: no emission, and a
                    // real event in it ends the path with nothing (and no coverage).
                    if (m.holdout() && path.history.vertices == 0) {
                        heldOut = chooseEvent(c, path, sampler).event != MediumEvent::Null;
                        return heldOut ? Track::Stop : Track::Continue;
                    }
                    if (m.emissive()) {
                        SampledSpectrum e;
                        scoreEmission(c, m, path, &e);
                        out.add(e, path.history.emitted(), kEmissionGroup,
                                view.at(path.history, c.t, false));
                    }
                    if (m.fluorescent() && fluoresce(m, c, ts, sampler, &path, &next, &lambdaIn)) {
                        scattered = path.alive();
                        eventT = c.t;
                        return Track::Stop;
                    }
                    const CollisionOutcome o = chooseEvent(c, path, sampler);
                    if (o.event == MediumEvent::Null) return Track::Continue;
                    if (o.event == MediumEvent::Scattered) {
                        out.addLit(path.beta, directLightMedium(scene, c, -ray.d, sampler, ts),
                                   path.history.gathered(false), ts.lightSplit,
                                   view.at(path.history, c.t, false));
                        view.scatter(path.history, c.t, false);
                        path.history.scatter(false);
                        next = Ray{c.p, samplePhase(m, c, ray.d, sampler, &path), kInfinity};
                        scattered = true;
                    }
                    return Track::Stop;  // scattered, or absorbed for good
                });
            if (data) data->walked(escaped);
            // A holdout seen before the path scattered is nothing to the camera: black, and
            // only what lies in front of it covers the pixel (docs/aovs.md, "Holdouts"). Light
            // that scattered meets it as any surface.
            const bool holdout = hit && path.history.vertices == 0 && geometry->holdout(*hit);
            if (depth == 0)
                out.alpha = escaped && (!hit || holdout)
                                ? clamp(1.f - path.beta.average(), 0.f, 1.f)
                            : heldOut ? 0.f
                                      : 1.f;
            if (heldOut) break;
            if (holdout && escaped) break;
            if (lambdaIn > 0.f) {
                SampledWavelengths li = ts.tracking.wavelengths();
                li.lambda.fill(lambdaIn);
                ts.tracking.setWavelengths(li);
                out.addLit(path.beta, directLightIsotropic(scene, next.o, sampler, ts),
                           path.history.gathered(false), ts.lightSplit,
                           view.at(path.history, eventT, false));
                view.scatter(path.history, eventT, false);
                path.history.scatter(false);
                fluoresced = true;
            }
            // Leaving the scene: the dome (camera ray or after mirrors and glass), light seen
            // straight from its source as emission is (docs/aovs.md).
            if (!scattered && escaped && !hit && specularChain && std::isinf(ray.tMax))
                out.add(path.beta *
                            escapedRadiance(scene, ray.d, ts.tracking.wavelengths(), depth == 0),
                        path.history.emitted(), kEmissionGroup, kUnplaced);
            if (scattered) specularChain = false;  // a medium event: NEE counted the dome
            if (!scattered && escaped && hit) {
                specularChain = specularChain && scene.geometry->materialAt(*hit).specular();
                scattered = scatterAtSurface(scene, guided, *hit, ray, ts.tracking.wavelengths(),
                                             sampler, ts, &path, &view, &out, &next);
            }
            if (!scattered) break;
            if (depth + 1 >= mMaxDepth) {
                mCapped.fetch_add(1, std::memory_order_relaxed);
                break;
            }
            if (!path.roulette(sampler)) break;
            ray = next;
        }
        if (fluoresced) ts.tracking.setWavelengths(w);  // the caller's, for its next path
        out.finish(path);
        return out;
    }

    IntegratorStats stats() const override {
        IntegratorStats s;
        s.cappedPaths = mCapped.load();
        return s;
    }

private:
    // The next direction from the medium's phase function; β times its weight p/pdf.
    static Vec3 samplePhase(const Medium& m, const Collision& c, const Vec3& dir, Sampler& sampler,
                            PathThroughput* path) {
        SampledSpectrum weight;
        float pdf;
        const float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        const Vec3 wo = m.phaseSample(c.mp, dir, uc, u1, u2, &weight, &pdf);
        path->beta *= weight;
        return wo;
    }

    // The inelastic event at a collision in a fluorescent medium (the top of the file). True
    // when it was chosen: the path goes on hero-only at *lambdaIn along *next (β may be 0 when
    // no λi feeds λo). Not chosen, β carries the ordinary events' factor 1 / (1 − P_f).
    static bool fluoresce(const Medium& m, const Collision& c, ThreadState& ts, Sampler& sampler,
                          PathThroughput* path, Ray* next, float* lambdaIn) {
        const InelasticEvent in = sampleInelasticEvent(
            m, ts.tracking.context(size_t(c.medium)), c.p, ts.tracking.wavelengths(), c.sigmaMaj,
            eventProbabilities(c, path->beta).pAbsorb, sampler);
        if (!in.chosen) {
            path->beta *= in.otherScale;
            return false;
        }
        const float hero = path->beta[0] * in.weight;
        path->keepHeroOnly();
        path->beta[0] = hero;
        if (hero > 0.f) {
            *lambdaIn = in.lambdaInNm;
            *next = Ray{c.p, in.wi, kInfinity};
        }
        return true;
    }

    // The surface vertex: emission, NEE on diffuse surfaces, then the BSDF sample that
    // continues the path. Returns false when the path ends here.
    static bool scatterAtSurface(const RenderScene& scene, bool guided, const SurfaceHit& hit,
                                 const Ray& ray, const SampledWavelengths& w, Sampler& sampler,
                                 ThreadState& ts, PathThroughput* path, DeepView* view,
                                 RadianceSample* out, Ray* next) {
        const Material& mat = scene.geometry->materialAt(hit);
        const DeepAt at = view->at(path->history, hit.t, true);
        if (mat.emissive())
            out->add(path->beta * mat.emission(w), path->history.emitted(), kEmissionGroup, at);
        if (!mat.specular())
            out->addLit(path->beta, directLightSurface(scene, hit, mat, -ray.d, sampler, ts),
                        path->history.gathered(true), ts.lightSplit, at);
        if (mat.specular())
            view->specular(path->history, hit.t);
        else
            view->scatter(path->history, hit.t, true);
        if (guided && !mat.specular())
            return continueAtDiffuse(scene, mat, hit, ray.d, w, sampler, path, next);
        return continueAtSurface(mat, hit, ray.d, w, TransportMode::Radiance, sampler, path, next);
    }

    int mMaxDepth;
    mutable std::atomic<uint64_t> mCapped{0};
};

}  // namespace

std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth) {
    return std::make_unique<VolPathIntegrator>(maxDepth);
}

}  // namespace mirage
