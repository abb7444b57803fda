// The reference integrator: a spectral volumetric path tracer. It is the ground truth for
// everything the photon mapper approximates, so it makes no approximation of its own: free
// flights by delta tracking against the majorant grid (null collisions), next-event estimation
// at every real scattering event with ratio-tracked shadow rays, phase-function sampling for
// the next direction, emission scored at every tentative collision, Russian roulette on the
// throughput. Lights are reached by next-event estimation only (they are not hit by rays); a
// quad or the dome is sampled by the light and by the phase function (render/direct_light.cpp),
// and point and spot lights also by a point drawn towards them along every segment, weighed
// against the scattering points' estimates (render/lamp_sampling.h): the lamp in the fog. Where
// such a lamp sits inside a medium, a share of the continuations head towards it ("Lobes
// towards lamps", below): the lamp seen past after a bounce.
// Emissive media are a light too: every real scattering vertex draws a line towards their
// glow and estimates its emission whole, the next flight's emission weighed against it
// (render/line_emission.h): smoke lit by its own flames. There a straight flight also draws a
// point along its ray towards the glow, which shares the emission with its collisions
// (render/flight_emission.h): thin flames that few collisions find.
//
// Weights (per wavelength; see transport/tracking.h):
//   emission      β σa Le / σ̄                    at every tentative collision (shared with the
//                                                 flight's point where media glow)
//   real          β ← β σs / (σ̄ (P_a + P_s))     it scatters, absorption a weight; then NEE
//                                                 and β ← β p/pdf (= 1 for one lobe)
//   null          β ← β σn / (σ̄ P_n)
// A path ends by leaving every medium, by roulette, where nothing scatters (σs = 0), or at the
// depth cap (counted in the summary: a capped path is a bias, however rare). Absorption is a
// weight, not an end (transport/path_vertex.h: chooseEvent).
//
// Curved light: behind the curved camera (render/curved_camera.h), where a [refraction] field
// bends light, every segment after the camera's chord follows its Fermat path (flyCurved) and
// the shadow rays towards lights at infinity bend too (render/direct_light.cpp), as the photon
// pass bends photons; radiance keeps L/n² along them (the n² law). Lobe walks and the lamps'
// distance sampling along a segment are straight: where light bends, neither is drawn.
//
// Lights at infinity (the dome): the light's own samples by NEE, and the phase function's by the
// path's continuation, which scores them where it leaves the scene (render/direct_light.cpp,
// MediumLights::SkyByEscape), both weighed by the power heuristic; a uniform dome by the
// continuation alone; the escape carries the lobe walks' share of the vertex that drew it, and
// its weight against the camera ray's points for the dome, as its NEE does (on sky-white, the
// cloud's core and rim were noisier when such a vertex drew a shadow ray instead: relMSE at 32
// spp 0.0099 → 0.0086 over three seeds, docs/regimes.md). Where a field bends the paths, both
// strategies stay shadow rays. A path also scores them on the camera ray and after
// mirrors and glass, where no NEE has. In a plain medium under domes alone the camera ray's lit
// point for the dome starts a second path (render/lamp_sampling.h: skyPointsFork), which `trace`
// follows after the first (guided where the first is), and delta tracking's scattering point
// there goes on with the probability of its weight against those points.
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
// the ordinary events, their weights divided by 1 − P_f.
#include <atomic>
#include <cmath>
#include <optional>

#include "render/camera_path.h"
#include "render/camera_ray_data.h"
#include "render/curved_transport.h"
#include "render/direct_light.h"
#include "render/inelastic_light.h"
#include "render/integrator.h"
#include "render/lamp_sampling.h"
#include "render/light_lobes.h"
#include "render/flight_emission.h"
#include "render/line_emission.h"
#include "render/lobe_walk.h"
#include "render/sun_shade.h"
#include "transport/path_vertex.h"
#include "transport/reemission.h"

namespace mirage {

namespace {

// Lobes towards lamps. Where a lamp sits inside a medium (render/light_lobes.h: lampsInMedia),
// the continuation from an unguided medium vertex is drawn from a one-sample mixture: the
// lamps' lobes (density ∝ 1/θ about the direction towards each lamp) with probability
// kLampLobeShare, the phase function otherwise, and β takes p / pdf_mix, pdf_mix = (1 − s)
// pdf_phase + s pdf_lobes (the balance heuristic over the mixture; Veach 1997, §9.2.4). So the
// next segment passes within D of the lamp with a probability ∝ D, and p / pdf_mix ∝ D cancels
// the 1/D of its equiangular point's estimate (render/lamp_sampling.h), whose second moment
// under the phase function's directions alone diverged as log D: the fireflies of dark pixels
// far from the lamp whose paths pass it after a bounce (docs/regimes.md). The mixture's density
// is what the flight's emission weight and the dome's escape read.
// Measured on the lamp-point regime (16 samples, three pairs of seeds, noise between them): 9.9
// by the phase function alone; s = 0.1 4.6 (one pair), 0.25 4.9, 0.4 3.8, 0.5 3.6, 0.7 11 (the
// phase function's own directions starved); lobes to 45° at s = 0.25, 4.1, to 180° 7.2 (half
// their directions lead away from the lamp). lamp-spot: 1400, 500 (0.25), 440 (0.4), 1140 (0.5,
// one pair at 2700): s = 0.4, lobes to 90°.

// How a flight along a path's ray ended: at the ray's end (the surface ahead, or out of the
// scene), by absorption (or at the collision cap), at a real event in a holdout medium the
// camera sees, by scattering at `at`, or by a fluorescent re-emission there.
struct Flight {
    enum class End { Escaped, Absorbed, HeldOut, Scattered, Reemitted } end = End::Absorbed;
    Collision at;          // Scattered, Reemitted
    float lambdaIn = 0.f;  // Reemitted: the wavelength the light was absorbed at, nm
    Vec3 wi;               // Reemitted: the direction the light was re-emitted in
};

// The tentative collisions along a straight ray over (0, tEnd), for VolPathIntegrator::fly.
auto straightTrack(ThreadState& ts, const Ray& ray, float tEnd, Sampler& sampler) {
    return [&ts, ray, tEnd, &sampler](auto&& visit) {
        return trackCollisions(ts.tracking, ray, tEnd, sampler, visit);
    };
}

class VolPathIntegrator : public Integrator {
public:
    explicit VolPathIntegrator(int maxDepth) : mMaxDepth(maxDepth) {}
    const IntegratorInfo& info() const override { return integratorInfo("volpath"); }
    bool lightShapedRadiance() const override { return true; }

    // The emissive media's power grid, where the scene has one and samples it
    // (render/line_emission.h); built per frame, from the still grids.
    // The lamps inside media whose lobes the continuations draw from (render/light_lobes.h).
    // Where the sky's sun is hidden from the media, which sets how often vertices draw the
    // lights at infinity (render/sun_shade.h).
    void preprocess(const RenderScene& scene, uint64_t) override {
        mEmission = scene.emissionSampling ? EmissionLight::forScene(scene) : nullptr;
        mLamps = lampsInMedia(scene);
        mSunShade = SunShade::forScene(scene);
    }

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        PathRecorder rec(&out, ts);
        CameraPath path(cameraRay, w);
        // Lobe walks (render/light_lobes.h) are straight: where paths bend, none is drawn.
        path.guided = !ts.curved && guidesPaths(scene);
        if (path.guided) path.walkStart = lobeWalkStart(scene);
        path.sunShade = mSunShade.get();
        std::optional<Fork> fork;
        trace(scene, sampler, ts, path, rec, &fork);
        if (fork) trace(scene, sampler, ts, fork->path, fork->rec, nullptr);
        if (path.reemitted) ts.tracking.setWavelengths(w);  // the caller's, for its next path
        rec.finish(path.throughput);
        return out;
    }

    IntegratorStats stats() const override {
        IntegratorStats s;
        s.cappedPaths = mCapped.load();
        return s;
    }

private:
    // The point of a straight flight along ray that shares its emission with its collisions
    // (render/flight_emission.h), where the scene's glowing media are a light.
    FlightEmission flightEmission(const Ray& ray, float tEnd, Sampler& sampler,
                                  ThreadState& ts) const {
        if (!mEmission || ts.curved) return FlightEmission();
        return FlightEmission(*mEmission, ray, tEnd, sampler, ts.tracking);
    }

    // A second path from the camera ray's point for the lights at infinity (skyPointsFork,
    // render/lamp_sampling.h), past its first vertex, with its branch of the sample's record.
    struct Fork {
        CameraPath path;
        PathRecorder rec;
    };

    // The path from its ray on, vertex after vertex, until it ends; on the camera ray, where
    // `fork` is given and the scene's points for the lights at infinity fork, the second path
    // they start.
    void trace(const RenderScene& scene, Sampler& sampler, ThreadState& ts, CameraPath& path,
               PathRecorder& rec, std::optional<Fork>* fork) const {
        // Lobe walks weigh next-event estimation against themselves; lamps draw their own
        // points only where they do not (render/lamp_sampling.h). The lights at infinity draw
        // theirs on the camera ray alone, where no walk from an earlier vertex passes: there
        // the points and delta tracking's scattering points are the only strategies, guided or
        // not.
        const bool towardsLamps = !path.guided && samplesLamps(scene);
        const bool towardsSky = samplesSky(scene);
        const bool forks = fork && !ts.curved && mMaxDepth > 1 && skyPointsFork(scene);
        for (;; ++path.depth) {
            // Where paths bend, every segment after the camera's (a chord the curved camera
            // hands over) follows its Fermat path.
            const bool bends = ts.curved && path.depth > 0;
            SurfaceAhead ahead = bends ? SurfaceAhead() : surfaceAhead(scene, path.ray);
            // The camera ray also draws points per medium for the lights at infinity.
            const bool sky = path.depth == 0 && towardsSky;
            LampSampling lamps(scene, path.ray, ahead.tEnd, towardsLamps && !bends, sampler,
                               sky ? &ts.tracking : nullptr, sky && forks);
            const SampledSpectrum betaAtStart = path.throughput.beta;
            const Flight f = bends ? flyCurved(scene, lamps, sampler, ts, path, rec, &ahead)
                                   : fly(straightTrack(ts, path.ray, ahead.tEnd, sampler),
                                         flightEmission(path.ray, ahead.tEnd, sampler, ts), lamps,
                                         sampler, ts, path, rec);
            std::optional<SkyFork> skyFork;
            if (!lamps.empty()) lamps.gather(scene, betaAtStart, sampler, ts, rec, &skyFork);
            if (skyFork) *fork = forkAt(scene, *skyFork, path, rec, sampler, ts);
            // What the camera sees through the flight: the plate, past nothing or a holdout.
            const bool plate = f.end == Flight::End::Escaped &&
                               (!ahead.hit || rec.holdout(*scene.geometry, *ahead.hit));
            if (f.end == Flight::End::HeldOut)
                rec.stoppedInHoldout();
            else
                rec.coverage(plate, path.throughput.beta.average());
            bool goesOn = false;
            if (f.end == Flight::End::Scattered) {
                goesOn = lamps.keepsScatterPoint(f.at, sampler);
                if (goesOn) scatterInMedium(scene, f.at, lamps, sampler, ts, path, rec);
            } else if (f.end == Flight::End::Reemitted) {
                reemit(scene, f, sampler, ts, path, rec);
                goesOn = true;
            } else if (f.end == Flight::End::Escaped && !ahead.hit) {
                escapeToDome(scene, path, ts, rec);
            } else if (f.end == Flight::End::Escaped && !plate) {
                goesOn = scatterAtSurface(scene, *ahead.hit, sampler, ts, path, rec);
            }
            if (!goesOn) break;
            if (path.depth + 1 >= mMaxDepth) {
                mCapped.fetch_add(1, std::memory_order_relaxed);
                break;
            }
            if (!path.throughput.roulette(sampler)) break;
        }
    }

    // The second path from the camera ray's point x for the lights at infinity: its
    // next-event estimate made (LampSampling::gather), it goes on along a phase-function sample,
    // with its own branch of the record from the camera ray on. Where paths are guided it is
    // guided as the first: x starts a lobe walk as any guided vertex does, and the walk's share
    // goes into the next vertex's weights (scatterInMedium). Unguided, the second path had
    // carried the sun's light in a sky map only by its vertices' shadow rays, a heavy tail
    // (sky-hdr's relMSE 0.14 → 0.16 with the points on); guided, 0.29 → 0.21 at 16 samples
    // (docs/regimes.md).
    Fork forkAt(const RenderScene& scene, const SkyFork& x, const CameraPath& camera,
                const PathRecorder& rec, Sampler& sampler, ThreadState& ts) const {
        Fork fork{CameraPath(camera.ray, camera.wavelengths), rec.branch()};
        CameraPath& path = fork.path;
        path.throughput.beta = x.beta;
        // Its roulette measures against the weight it starts with, at most 1 (PathThroughput).
        const float start = x.beta.maxValue();
        if (start > 0.f && start < 1.f) path.throughput.rouletteScale = start;
        fork.rec.scatteredInMedium(x.at.t);
        path.specularChain = false;
        path.skyDark = x.sky.dark;
        path.sunShade = camera.sunShade;
        path.guided = camera.guided;
        path.walkStart = camera.walkStart;
        const LightLobes lobes =
            path.guided ? walkFrom(scene, x.at, path, sampler, ts, fork.rec) : LightLobes();
        float pdf;
        const Vec3 dir = samplePhase(ts.tracking.medium(x.at.medium), x.at, path.ray.d, sampler,
                                     &path.throughput, &pdf);
        path.leaveSkyToEscape(pdf, 1.f, x.sky.rate);
        path.lobeRatios = walkShare(lobes, path, dir, pdf);
        path.ray = Ray{x.at.p, dir, kInfinity};
        path.depth = 1;
        return fork;
    }

    // The flight along the path's ray, its tentative collisions handed over by `track` (true
    // when the ray got through): emission scored at every tentative collision, then the event
    // chosen there (transport/path_vertex.h), or in a fluorescent medium first the inelastic
    // one (fluoresce). A holdout medium the camera sees only attenuates: no emission, and a
    // real event in it ends the path with nothing. The lamps' points on the segment read their
    // transmittance off the flight (render/lamp_sampling.h).
    template <typename Tracker>
    static Flight fly(Tracker&& track, FlightEmission emission, LampSampling& lamps,
                      Sampler& sampler, ThreadState& ts, CameraPath& path, PathRecorder& rec) {
        Flight f;
        CameraRayData* data = rec.cameraRayData();
        PathThroughput& throughput = path.throughput;
        const bool reached = track([&](const Collision& c) {
            emission.reached(c.t, throughput.beta, path.emissionWeight, ts.tracking, rec);
            if (data) data->seen(c);
            lamps.seen(c, ts.tracking);
            const Medium& m = ts.tracking.medium(c.medium);
            if (rec.holdout(size_t(c.medium))) {
                if (chooseEvent(c, throughput, sampler).event == MediumEvent::Null)
                    return Track::Continue;
                f.end = Flight::End::HeldOut;
                return Track::Stop;
            }
            if (m.emissive()) {
                SampledSpectrum e;
                scoreEmission(c, m, throughput, &e);
                const float w = path.emissionWeight * emission.collisionShare(c, ts.tracking);
                rec.emittedInMedium(e * w, c.t, c.mp.temperature);
            }
            if (m.fluorescent() && fluoresce(m, c, sampler, ts, throughput, &f)) return Track::Stop;
            const MediumEvent e = chooseEvent(c, throughput, sampler).event;
            if (e == MediumEvent::Null) return Track::Continue;
            if (e == MediumEvent::Scattered) {
                f.end = Flight::End::Scattered;
                f.at = c;
            }
            return Track::Stop;  // scattered, or absorbed for good
        });
        if (reached) {
            f.end = Flight::End::Escaped;
            emission.reached(kInfinity, throughput.beta, path.emissionWeight, ts.tracking, rec);
        }
        lamps.flightEnded(reached);
        rec.cameraFlightEnded(reached);
        return f;
    }

    // The flight along the curved (Fermat) path from the path's ray where a [refraction] field
    // bends light (render/curved_transport.h), its collisions handled as fly's. Where it ends,
    // path.ray becomes the chord it was on (the direction a scattering there sees it arrive
    // from; the ray that met a surface) or, where it left the scene, the straight ray on; and β
    // takes the n² law's factor from there back to the segment's start: radiance found at
    // index n counts (n_start/n)² at the start. Emission along the segment is counted at the
    // start's index (in air they differ by < 1e−4). A path that has walked the curved length
    // (CurvedWalk::maxArc) without leaving the scene goes on straight, as camera rays do
    // (render/curved_camera.h); cut by the stepper's cap, it is counted with the capped paths.
    Flight flyCurved(const RenderScene& scene, LampSampling& lamps, Sampler& sampler,
                     ThreadState& ts, CameraPath& path, PathRecorder& rec,
                     SurfaceAhead* ahead) const {
        using Kind = CurvedWalkEnd::Kind;
        const CurvedTransport& curved = *ts.curved;
        const float lambda = path.wavelengths.lambda[0];
        const double nStart = curved.index(path.ray.o, lambda);
        std::optional<SurfaceHit> hit;
        const CurvedWalk walk = curved.flight(&hit);
        CurvedWalkEnd end;
        auto track = [&](auto&& visit) {
            end = trackCurvedCollisions(ts.tracking, walk, path.ray, lambda, sampler,
                                        [&](const Collision& c, float) { return visit(c); });
            return end.kind != Kind::Stopped;
        };
        const Flight f = fly(track, FlightEmission(), lamps, sampler, ts, path, rec);
        path.throughput.beta *= radianceIndexScale(curved.index(end.p, lambda), nStart);
        if (end.kind == Kind::Reached || end.kind == Kind::Capped) {
            if (end.kind == Kind::Capped) mCapped.fetch_add(1, std::memory_order_relaxed);
            path.ray = Ray{end.p, end.direction, kInfinity};
            *ahead = surfaceAhead(scene, path.ray);
            return fly(straightTrack(ts, path.ray, ahead->tEnd, sampler), FlightEmission(), lamps,
                       sampler, ts, path, rec);
        }
        if (end.kind == Kind::Left) {
            path.ray = Ray{end.p, end.direction, kInfinity};
            return f;
        }
        path.ray = Ray{end.chord.o, end.chord.d, kInfinity};
        if (end.kind == Kind::Surface) *ahead = SurfaceAhead{hit, hit ? hit->t : 0.f};
        return f;
    }

    // A lobe walk from the guided medium vertex x, started with the path's probability
    // walkStart (render/lobe_walk.h); the lights' lobes at x, for walkShare.
    LightLobes walkFrom(const RenderScene& scene, const Collision& x, const CameraPath& path,
                        Sampler& sampler, ThreadState& ts, const PathRecorder& rec) const {
        const LightLobes lobes(scene, x.p, path.wavelengths);
        if (!lobes.empty() && (path.walkStart >= 1.f || sampler.get1D() < path.walkStart))
            walkFromMedium(scene, lobes, x, path, mMaxDepth, sampler, ts, rec);
        return lobes;
    }
    // The walk's share in the weights of the vertex the continuation dir (drawn with density
    // pdf) reaches: its density of dir, in the walk's expected count, against pdf.
    static float walkShare(const LightLobes& lobes, const CameraPath& path, const Vec3& dir,
                           float pdf) {
        return lobes.empty() ? 0.f : path.walkStart * lobes.pdf(dir) / pdf;
    }

    // A real scattering event at x: next-event estimation, weighed against the lobe walks of the
    // run x belongs to and the segment's points towards the lamps, a line sample of the emissive
    // media's light (render/line_emission.h), a lobe walk of its own where paths are guided, and
    // the phase function's sample that continues the path, its flight's emission weighed
    // against the line samples.
    void scatterInMedium(const RenderScene& scene, const Collision& x, const LampSampling& lamps,
                         Sampler& sampler, ThreadState& ts, CameraPath& path,
                         PathRecorder& rec) const {
        const float ratios = path.lobeRatios;  // the run's sum on the segment that reached x
        // The lights at infinity are left to the path's continuation where no field bends the
        // path. Its escape then counts as x's estimate does: with the lobe walks' share
        // 1/(1 + ratios) and x's weight against the camera ray's points for them
        // (LampSampling::skyWeight). At the depth cap there is no continuation to leave them to.
        const bool last = path.depth + 1 >= mMaxDepth;
        const bool escapes = !ts.curved && !last;
        const float share = lamps.skyWeight(x) / (1.f + ratios);
        SkyDraws sky{path.skyDark, path.sunShade};
        rec.litInMedium(
            path.throughput.beta / (1.f + ratios),
            directLightMedium(scene, x, -path.ray.d, sampler, ts, lamps.empty() ? nullptr : &lamps,
                              escapes ? MediumLights::SkyByEscape : MediumLights::All, &sky),
            x.t);
        path.skyDark = sky.dark;
        rec.scatteredInMedium(x.t);
        path.specularChain = false;  // a medium event: next-event estimation counted the dome
        path.escapePdf = 0.f;
        // Where paths bend, the flight is no line: the emission stays the flight's alone.
        const EmissionLight* line = ts.curved ? nullptr : mEmission.get();
        if (line)
            sampleLineEmission(scene, *line, x, path.ray.d, path.throughput.beta, last, sampler, ts,
                               rec);
        const Medium& m = ts.tracking.medium(x.medium);
        if (!path.guided || last) {
            float pdf = 0.f;
            const Vec3 dir = continueInMedium(m, x, sampler, ts, path, last, &pdf);
            path.emissionWeight =
                line ? flightEmissionWeight(*line, x.p, dir, pdf, ts.tracking) : 1.f;
            if (escapes) path.leaveSkyToEscape(pdf, share, sky.rate);
            path.ray = Ray{x.p, dir, kInfinity};
            path.lobeRatios = 0.f;
            return;
        }
        const LightLobes lobes = walkFrom(scene, x, path, sampler, ts, rec);
        float pdf;
        const Vec3 dir = samplePhase(m, x, path.ray.d, sampler, &path.throughput, &pdf);
        if (escapes) path.leaveSkyToEscape(pdf, share, sky.rate);
        // Walks from earlier vertices pass this one even where no light has a lobe (outside a
        // spot's cone): their share decays all the same.
        path.lobeRatios = kLobeWalkGoesOn * ratios + walkShare(lobes, path, dir, pdf);
        path.emissionWeight = line ? flightEmissionWeight(*line, x.p, dir, pdf, ts.tracking) : 1.f;
        path.ray = Ray{x.p, dir, kInfinity};
    }

    // The path fluoresced at f.at (fluoresce): from here it carries the absorbed wavelength λi,
    // gathers next-event estimation through the isotropic lobe of re-emission
    // (render/inelastic_light.h), and goes on along the re-emitted direction.
    static void reemit(const RenderScene& scene, const Flight& f, Sampler& sampler, ThreadState& ts,
                       CameraPath& path, PathRecorder& rec) {
        path.wavelengths.lambda.fill(f.lambdaIn);
        ts.tracking.setWavelengths(path.wavelengths);
        path.reemitted = true;
        rec.litInMedium(path.throughput.beta, directLightIsotropic(scene, f.at.p, sampler, ts),
                        f.at.t);
        rec.scatteredInMedium(f.at.t);
        path.specularChain = false;
        path.lobeRatios = 0.f;      // no lobe walk crosses a re-emission
        path.emissionWeight = 1.f;  // nor a line sample (render/line_emission.h)
        path.escapePdf = 0.f;
        path.ray = Ray{f.at.p, f.wi, kInfinity};
    }

    // The surface vertex: emission and, where it is diffuse, next-event estimation
    // (gatherAtSurface), then the BSDF sample that continues the path. Returns false when the
    // path ends here. Where paths are guided, a diffuse vertex starts a lobe walk and the run of
    // medium vertices that follows begins with its ratio.
    bool scatterAtSurface(const RenderScene& scene, const SurfaceHit& hit, Sampler& sampler,
                          ThreadState& ts, CameraPath& path, PathRecorder& rec) const {
        const Material& mat = gatherAtSurface(scene, hit, true, sampler, ts, path, rec);
        path.lobeRatios = 0.f;
        path.emissionWeight = 1.f;  // a surface draws no line sample
        const bool walks = path.guided && !mat.specular() && path.depth + 1 < mMaxDepth;
        const LightLobes lobes = walks ? LightLobes(scene, hit.p, path.wavelengths) : LightLobes();
        if (!lobes.empty()) walkFromSurface(scene, lobes, hit, path, mMaxDepth, sampler, ts, rec);
        const Vec3 dirIn = path.ray.d;
        if (!continueAtSurface(mat, hit, path.wavelengths, TransportMode::Radiance, sampler, &path))
            return false;
        if (lobes.empty()) return true;
        const Frame frame(hit.ns);
        const float pdf = mat.pdf(frame.toLocal(-dirIn), frame.toLocal(path.ray.d));
        path.lobeRatios = pdf > 0.f ? lobes.pdf(path.ray.d) / pdf : 0.f;
        return true;
    }

    // The continuation's direction from the unguided medium vertex x: the phase function's, or
    // where lamps sit inside the media a one-sample mixture of it and the lamps' lobes ("Lobes
    // towards lamps"); β times p / pdf, *pdf the density it was drawn with. At the depth cap, and
    // where paths bend (no segment draws points towards lamps), the phase function alone.
    Vec3 continueInMedium(const Medium& m, const Collision& x, Sampler& sampler,
                          const ThreadState& ts, CameraPath& path, bool last, float* pdf) const {
        const bool lamps = !mLamps.empty() && !ts.curved && !last;
        const LightLobes lobes = lamps ? LightLobes::towardsLamps(mLamps, x.p) : LightLobes();
        if (lobes.empty()) return samplePhase(m, x, path.ray.d, sampler, &path.throughput, pdf);
        const float u = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        const Vec3 dirIn = path.ray.d;
        Vec3 dir;
        if (u < kLampLobeShare) {
            dir = lobes.sample(u / kLampLobeShare, u1, u2);
        } else {
            SampledSpectrum phaseWeight;
            float phasePdf;
            dir = m.phaseSample(x.mp, dirIn, (u - kLampLobeShare) / (1.f - kLampLobeShare), u1, u2,
                                &phaseWeight, &phasePdf);
        }
        *pdf =
            (1.f - kLampLobeShare) * m.phasePdf(x.mp, dirIn, dir) + kLampLobeShare * lobes.pdf(dir);
        path.throughput.beta *=
            *pdf > 0.f ? m.phaseEval(x.mp, dirIn, dir) / *pdf : SampledSpectrum(0.f);
        return dir;
    }

    // The inelastic event at a collision in a fluorescent medium (the top of the file). True
    // when it was chosen, and the flight ends: *f says Reemitted (β hero-only, as after
    // dispersion), or Absorbed when no λi feeds λo (β = 0). Not chosen, β carries the ordinary
    // events' factor 1 / (1 − P_f).
    static bool fluoresce(const Medium& m, const Collision& c, Sampler& sampler, ThreadState& ts,
                          PathThroughput& path, Flight* f) {
        const InelasticEvent in = sampleInelasticEvent(
            m, ts.tracking.context(size_t(c.medium)), c.p, ts.tracking.wavelengths(), c.sigmaMaj,
            eventProbabilities(c, path.beta).pAbsorb, sampler);
        if (!in.chosen) {
            path.beta *= in.otherScale;
            return false;
        }
        const float hero = path.beta[0] * in.weight;
        path.keepHeroOnly();
        path.beta[0] = hero;
        if (hero > 0.f) {
            f->end = Flight::End::Reemitted;
            f->at = c;
            f->lambdaIn = in.lambdaInNm;
            f->wi = in.wi;
        }
        return true;
    }

    int mMaxDepth;
    mutable std::atomic<uint64_t> mCapped{0};
    std::unique_ptr<EmissionLight> mEmission;  // null: emission found by flights alone
    std::vector<MediumLamp> mLamps;            // empty: continuations by the phase function
    std::unique_ptr<SunShade> mSunShade;       // null: the sky's draws by SkyDraws::dark
};

}  // namespace

std::unique_ptr<Integrator> makeVolPathIntegrator(int maxDepth) {
    return std::make_unique<VolPathIntegrator>(maxDepth);
}

}  // namespace mirage
