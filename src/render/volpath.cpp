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
#include <optional>

#include "render/camera_ray_data.h"
#include "render/direct_light.h"
#include "render/inelastic_light.h"
#include "render/integrator.h"
#include "render/light_lobes.h"
#include "transport/path_vertex.h"
#include "transport/reemission.h"

namespace mirage {

namespace {

// The probability that a lobe walk goes on past each of its vertices (lobeWalk).
constexpr float kLobeWalkGoesOn = 0.75f;

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
        const bool guided = guidesPaths(scene);  // render/light_lobes.h
        // Σ_j r_j q^(k−1−j) over the medium vertices j before this one in an unbroken run: the
        // weight of the lobe walks against the path's own samples (lobeWalk, below).
        float lobeRatios = 0.f;
        for (int depth = 0;; ++depth) {
            Ray next;
            const float ratios = lobeRatios;  // set by the medium vertex this segment leaves
            lobeRatios = 0.f;
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
                    if (scene.holdout(size_t(c.medium)) && path.history.vertices == 0) {
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
                        out.addLit(path.beta / (1.f + ratios),
                                   directLightMedium(scene, c, -ray.d, sampler, ts),
                                   path.history.gathered(false), ts.lightSplit,
                                   view.at(path.history, c.t, false));
                        view.scatter(path.history, c.t, false);
                        path.history.scatter(false);
                        if (guided && depth + 1 < mMaxDepth) {
                            const LightLobes lobes(scene, c.p, ts.tracking.wavelengths());
                            if (!lobes.empty())
                                walkFromMedium(scene, lobes, c, ray.d, path, ratios, depth, view,
                                               sampler, ts, &out);
                            float pdf;
                            next =
                                Ray{c.p, samplePhase(m, c, ray.d, sampler, &path, &pdf), kInfinity};
                            // Walks from earlier vertices pass this one even where no light
                            // has a lobe (outside a spot's cone): their share decays all the same.
                            lobeRatios = kLobeWalkGoesOn * ratios +
                                         (lobes.empty() ? 0.f : lobes.pdf(next.d) / pdf);
                        } else {
                            next = Ray{c.p, samplePhase(m, c, ray.d, sampler, &path), kInfinity};
                        }
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
                scattered =
                    scatterAtSurface(scene, guided, *hit, ray, ts.tracking.wavelengths(), depth,
                                     sampler, ts, &path, &view, &out, &next, &lobeRatios);
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
                            PathThroughput* path, float* pdfOut = nullptr) {
        SampledSpectrum weight;
        float pdf;
        const float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        const Vec3 wo = m.phaseSample(c.mp, dir, uc, u1, u2, &weight, &pdf);
        if (pdfOut) *pdfOut = pdf;
        path->beta *= weight;
        return wo;
    }

    // Lobe walks (render/light_lobes.h). In a strongly forward medium under a light, the
    // light a medium vertex receives after more scatterings comes mostly along the light's
    // beam: the next vertices' phase functions score up to p(0) there (26/sr for sea water's
    // particles), and a path that turns up the beam meets several such vertices in a row. The
    // path's phase samples, drawn about its own direction, find the beam rarely and brightly.
    // So each medium vertex x_i also starts a walk whose first direction is drawn from the
    // lobes about the lights and whose next ones from the phase function, going on past each
    // of its real collisions with probability q (kLobeWalkGoesOn), scoring next-event
    // estimates on the way; it ends at a surface, at an absorption, outside the media.
    //
    // A next-event estimate at the k-th vertex of a run of medium vertices can then come from
    // the path itself or from the walk started at any earlier vertex j of the run. Their
    // densities differ in one direction and in the q's, so the balance heuristic (Veach 1997,
    // §9.2) weighs every one of them by
    //     1 / (1 + Σ_j r_j q^(k−1−j)),  r_j = pdf_lobes(ω_j) / pdf_phase(ω_j),
    // on the directions the estimate's own path took, with its throughput taken as if every
    // direction had been drawn from the phase function (p/pdf_phase). The sum is kept along the
    // path (lobeRatios: S ← q S + r at each vertex). No walk crosses a surface or a
    // re-emission, so the sum restarts there; a diffuse surface starts a walk of its own, the
    // BSDF in the phase function's place, and its r begins the next run (the sand under a
    // sunlit sea, the walls of a lit water box). Weights never exceed one, and the path's own
    // throughput is untouched, so the long paths of a dense sea gain no product of weights (a
    // one-sample mixture of phase and lobes at each vertex, weighing p / (½ p + ½ pdf_lobes),
    // up to 2, made bright outliers in green water).
    //
    // Measured on the gallery's underwater scene (24×16 pixels, 1024 samples, relMSE against
    // 4× the samples): 0.26 with guided surface continuations alone, 0.020 with walks from
    // medium vertices (q = 0.75; 0.022 at q = 0.5, 0.020 at 0.9 for more time), 0.013 with
    // walks from the sand too, for 1.32× the instructions per sample (callgrind, 64 samples):
    // 15× less time to the same error.

    // The walk from a medium vertex x that the path reached along dirIn, ratios its sum there.
    void walkFromMedium(const RenderScene& scene, const LightLobes& lobes, const Collision& x,
                        const Vec3& dirIn, const PathThroughput& path, float ratios, int depth,
                        const DeepView& view, Sampler& sampler, ThreadState& ts,
                        RadianceSample* out) const {
        const float ul = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        const Vec3 dir = lobes.sample(ul, u1, u2);
        const Medium& m = ts.tracking.medium(x.medium);
        const float pdf = m.phasePdf(x.mp, dirIn, dir);
        if (!(pdf > 0.f)) return;
        PathThroughput walk = path;
        walk.beta *= m.phaseEval(x.mp, dirIn, dir) / pdf;
        lobeWalk(scene, Ray{x.p, dir, kInfinity}, kLobeWalkGoesOn * ratios + lobes.pdf(dir) / pdf,
                 depth, view, sampler, ts, &walk, out);
    }

    // The walk from a diffuse surface vertex, where a run of medium vertices begins: the BSDF
    // takes the phase function's place (f |cos| and its pdf).
    void walkFromSurface(const RenderScene& scene, const LightLobes& lobes, const Material& mat,
                         const SurfaceHit& hit, const Vec3& dirIn, const PathThroughput& path,
                         int depth, const DeepView& view, Sampler& sampler, ThreadState& ts,
                         RadianceSample* out) const {
        const float ul = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        const Vec3 dir = lobes.sample(ul, u1, u2);
        // A Lambertian surface reflects only: a lobe's direction through it scores f = 0.
        if ((dot(dir, hit.ng) > 0.f) != (dot(-dirIn, hit.ng) > 0.f)) return;
        const Frame frame(hit.ns);
        const Vec3 woL = frame.toLocal(-dirIn), wiL = frame.toLocal(dir);
        const float pdf = mat.pdf(woL, wiL);
        if (!(pdf > 0.f)) return;
        PathThroughput walk = path;
        walk.beta *= mat.eval(woL, wiL, ts.tracking.wavelengths()) * (std::abs(wiL.z) / pdf);
        walk.history.scatter(true);
        lobeWalk(scene, spawnRay(hit, dir), lobes.pdf(dir) / pdf, depth, view, sampler, ts, &walk,
                 out);
    }

    // A lobe walk from its first ray on, its first direction's weight in walk->beta and its
    // sum in ratios.
    void lobeWalk(const RenderScene& scene, Ray ray, float ratios, int depth, const DeepView& view,
                  Sampler& sampler, ThreadState& ts, PathThroughput* walkPtr,
                  RadianceSample* out) const {
        PathThroughput& walk = *walkPtr;
        for (int d = depth + 1; walk.alive() && d < mMaxDepth; ++d) {
            float tEnd = kInfinity;
            if (scene.hasSurfaces())
                if (const auto hit = scene.geometry->intersect(ray)) tEnd = hit->t;
            std::optional<Collision> y;
            trackCollisions(ts.tracking, ray, tEnd, sampler, [&](const Collision& c) {
                const MediumEvent e = chooseEvent(c, walk, sampler).event;
                if (e == MediumEvent::Null) return Track::Continue;
                if (e == MediumEvent::Scattered) y = c;
                return Track::Stop;
            });
            if (!y) return;
            out->addLit(
                walk.beta / (1.f + ratios), directLightMedium(scene, *y, -ray.d, sampler, ts),
                walk.history.gathered(false), ts.lightSplit, view.at(walk.history, y->t, false));
            walk.history.scatter(false);
            if (sampler.get1D() >= kLobeWalkGoesOn) return;
            float pdf;
            const Vec3 dir =
                samplePhase(ts.tracking.medium(y->medium), *y, ray.d, sampler, &walk, &pdf);
            ratios = kLobeWalkGoesOn * ratios +
                     LightLobes(scene, y->p, ts.tracking.wavelengths()).pdf(dir) / pdf;
            ray = Ray{y->p, dir, kInfinity};
        }
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
    // continues the path. Returns false when the path ends here. Where paths are guided, a
    // diffuse vertex starts a lobe walk and *ratios the sum of the run of medium vertices
    // that follows.
    bool scatterAtSurface(const RenderScene& scene, bool guided, const SurfaceHit& hit,
                          const Ray& ray, const SampledWavelengths& w, int depth, Sampler& sampler,
                          ThreadState& ts, PathThroughput* path, DeepView* view,
                          RadianceSample* out, Ray* next, float* ratios) const {
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
        if (!guided || mat.specular() || depth + 1 >= mMaxDepth)
            return continueAtSurface(mat, hit, ray.d, w, TransportMode::Radiance, sampler, path,
                                     next);
        const LightLobes lobes(scene, hit.p, w);
        if (lobes.empty())
            return continueAtSurface(mat, hit, ray.d, w, TransportMode::Radiance, sampler, path,
                                     next);
        walkFromSurface(scene, lobes, mat, hit, ray.d, *path, depth, *view, sampler, ts, out);
        if (!continueAtSurface(mat, hit, ray.d, w, TransportMode::Radiance, sampler, path, next))
            return false;
        const Frame frame(hit.ns);
        const float pdf = mat.pdf(frame.toLocal(-ray.d), frame.toLocal(next->d));
        *ratios = pdf > 0.f ? lobes.pdf(next->d) / pdf : 0.f;
        return true;
    }

    int mMaxDepth;
    mutable std::atomic<uint64_t> mCapped{0};
};

}  // namespace

std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth) {
    return std::make_unique<VolPathIntegrator>(maxDepth);
}

}  // namespace mirage
