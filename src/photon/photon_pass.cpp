// The photon pass: emission ∝ power, flights by photon_walk, stored scattering events.
//
// Power bookkeeping. A light l of power Φ_l is chosen with probability Φ_l/Φ (Φ = Σ Φ_l) and
// emits with the light's own PhotonEmission::weight w (mean 1), so a photon carries
// Φ_l / (N Φ_l/Φ) × w = (Φ/N) w watts: every photon of every light starts with the same
// power when the lights sample their emission exactly. The albedo roulette keeps that power
// through the walk (photon_walk.h); only a spectral phase mixture could change it, by p/pdf,
// and a fluorescent re-emission, by λi/λo (energy: Γ counts photons, Mobley 1994 §5.13).
//
// Emissive media (fire) are sources beside the lights: a MediumEmitter (medium_emitter.h) of
// tabulated power Φ_m is chosen with probability Φ_m/Φ, Φ now summing lights and media, and its
// photons carry (Φ/N) × w with the emitter's weight w. Emission seen directly is the render
// pass's (σa·Le along the camera ray); a photon stores only where it scatters, and its first
// scattering is stored too, since no shadow ray of the render pass reaches an emissive medium.
#include "photon/photon_pass.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/clock.h"
#include "core/interrupt.h"
#include "core/sampling.h"
#include "photon/medium_emitter.h"
#include "photon/photon_blocks.h"
#include "photon/photon_walk.h"
#include "photon/projection_map.h"
#include "transport/path_vertex.h"
#include "transport/surface_step_cap.h"

namespace mirage {

namespace {

// Source choice ∝ power: a discrete distribution by its cumulative sum over the sources' powers
// (W; negative counts as 0).
class LightChooser {
public:
    explicit LightChooser(const std::vector<double>& powers) {
        double sum = 0.0;
        for (double p : powers) {
            sum += std::max(0.0, p);
            mCdf.push_back(sum);
        }
        mTotal = sum;
    }
    double totalPower() const { return mTotal; }
    // Index of the source for u in [0, 1); sources of zero power are never chosen.
    size_t choose(float u) const {
        double target = double(u) * mTotal;
        size_t i = size_t(std::upper_bound(mCdf.begin(), mCdf.end(), target) - mCdf.begin());
        return std::min(i, mCdf.size() - 1);
    }

private:
    std::vector<double> mCdf;
    double mTotal = 0.0;
};

struct PhotonPath {
    bool capped = false;
    bool fromMedium = false;               // emitted by an emissive medium
    uint32_t light = Photon::kFromMedium;  // the light it left (Photon::light)
    double power = 0.0;                    // W the photon left its source with
    bool nonFinite = false;                // a photon with non-finite power or position was dropped
};

// What photons start from: the lights, then the emissive media, chosen ∝ power; and the
// lights' projection maps, where the caustic stream starts.
struct PhotonSources {
    const std::vector<const Light*>& lights;
    std::vector<MediumEmitter> emitters;
    std::vector<size_t> emitterMedium;  // index of each emitter's medium in the pass's media
    Bounds3 bounds;                     // of the media and surfaces: lights aim photons at it
    double mediumPower = 0.0;           // W, summed over the emitters' tables
    ProjectionPlan projection;

    PhotonSources(const std::vector<const Light*>& l, const std::vector<const Medium*>& media,
                  const Bounds3& b, ProjectionPlan plan)
        : lights(l), bounds(b), projection(std::move(plan)) {
        for (size_t i = 0; i < media.size(); ++i)
            if (media[i]->emissive() && !media[i]->homogeneous()) {
                emitters.emplace_back(*media[i]);
                emitterMedium.push_back(i);
                mediumPower += emitters.back().tablePower();
            }
    }
    // The main stream's sources' powers: the lights' into the scene, then the media's.
    std::vector<double> powers() const {
        std::vector<double> p;
        for (const Light* l : lights) p.push_back(double(l->emittedPower(bounds)));
        for (const MediumEmitter& e : emitters) p.push_back(e.tablePower());
        return p;
    }
    // The caustic stream's: each light's projection map's (0 for none).
    std::vector<double> projectedPowers() const {
        std::vector<double> p;
        for (const auto& map : projection.maps) p.push_back(map ? map->power() : 0.0);
        return p;
    }
};

// A photon reaches a map only if everything an estimate reads from it is finite: one NaN or ∞
// power would poison every estimate whose search finds it. The path ends at such a photon.
bool finitePhoton(const Photon& ph) {
    return std::isfinite(ph.power) && isFinite(ph.p) && isFinite(ph.wi) && std::isfinite(ph.lambda);
}

// Where a photon walk is, between two vertices: its ray, and its throughput, whose β[0] is the
// photon's power (W; monochromatic).
struct PhotonState : PathSegment {
    bool direct;        // no interaction yet: light straight from the light
    bool specularOnly;  // every interaction so far was a mirror or glass
    // Its light has a projection map, so its first event decides whether the path is this
    // stream's (projection_map.h); causticStream: it was emitted from that map.
    // lifted: a caustic photon past its first diffuse or medium event (liftToMainPower).
    bool projected = false, causticStream = false, lifted = false;
    int bounces = 0;
};

// Appends a photon to `list` when it is finite; false (and the path ends) when it is not.
// Stores ph at the walk's time (motion blur; 0 for a still pass), tagged with its light.
bool storePhoton(Photon ph, const PhotonWalk& walk, PhotonList* list, PhotonPath* path) {
    if (!finitePhoton(ph)) {
        path->nonFinite = true;
        return false;
    }
    ph.time = walk.timeOffset();
    ph.light = path->light;
    list->push_back(ph);
    return true;
}

// A stream of photons: its sources' choice ∝ power, and the power each photon leaves with
// before its source's weight (W: Φ/N of the stream).
struct PhotonStream {
    LightChooser chooser;
    float photonPower;
};

// One photon pass's walk of its photons: the sources, the main stream (photon indices below
// mainCount) and the caustic stream of the projection maps (the indices from mainCount on), the
// pass's settings and its surfaces (null: none).
class PhotonTracer {
public:
    PhotonTracer(const PhotonSources& sources, const PhotonStream& main,
                 const PhotonStream& caustic, uint64_t mainCount,
                 const PhotonPassSettings& settings, const GeometryScene* geometry)
        : mSources(sources),
          mMain(main),
          mCaustic(caustic),
          mMainCount(mainCount),
          mSettings(settings),
          mGeometry(geometry) {}

    // Photon `index`: emission, then flights until it leaves every medium and surface, is
    // absorbed, or has interacted maxBounces times. Appends its stored photons to *out.
    PhotonPath trace(uint64_t index, PhotonWalk& walk, PhotonMapLists* out) const {
        PhotonPath path;
        Sampler sampler(mSettings.seed, index, 0);
        if (mSettings.shutterClose != mSettings.shutterOpen)
            walk.tracking().setTimeOffset(shutterTime(index));
        PhotonState state;
        if (!emit(index, sampler, walk, &path, &state)) return path;
        for (;;) {
            std::optional<SurfaceHit> hit;
            const FlightEvent ev = fly(sampler, walk, &state, &path, &hit);
            if (state.direct && state.projected && !ownsFirstEvent(ev, hit, state)) return path;
            bool goesOn;
            if (ev.end == FlightEnd::Escaped && hit)
                goesOn = atSurface(*hit, sampler, walk, &state, &path, out);
            else if (ev.end == FlightEnd::Scattered || ev.end == FlightEnd::Reemitted)
                goesOn = inMedium(ev, walk, &state, &path, out);
            else
                goesOn = false;
            if (!goesOn || !liftToMainPower(sampler, &state)) return path;
            if (++state.bounces >= mSettings.maxBounces) {
                path.capped = true;
                return path;
            }
        }
    }

private:
    // Photon index's time in the shutter, from a stream of its own, like the camera's
    // (render/camera.h, shutterTime): every other number of the photon's walk is the one a
    // still pass draws.
    float shutterTime(uint64_t index) const {
        Sampler stream(hashCombine(mSettings.seed, 0x5b7e1f3a9c2d4e61ull), index, 0);
        return mSettings.shutterOpen +
               (mSettings.shutterClose - mSettings.shutterOpen) * stream.get1D();
    }

    // Projection maps split a projected light's paths by their first event: a hit on a mirror
    // or glass is the caustic stream's, anything else (a medium event, a diffuse surface, an
    // escape) the main stream's.
    bool ownsFirstEvent(const FlightEvent& ev, const std::optional<SurfaceHit>& hit,
                        const PhotonState& state) const {
        const bool specular =
            ev.end == FlightEnd::Escaped && hit && mGeometry->materialAt(*hit).specular();
        return specular == state.causticStream;
    }

    // A caustic photon is as dense as its projection makes it only up to its first diffuse or
    // medium event, the one it was aimed for (stored: the caustic map's, or a volume caustic).
    // Past it the light is no longer focused: a roulette with survival β/p lifts it to the main
    // stream's power p (unbiased, as every roulette of the walk), so that a k-nearest estimate
    // of the fog it diffuses into meets photons of one power, not a swarm of faint ones beside
    // a few bright ones (whose mixture multiplies the estimate's noise), and the stream costs
    // little past its caustic. False when the photon is absorbed.
    bool liftToMainPower(Sampler& sampler, PhotonState* state) const {
        if (!state->causticStream || state->specularOnly || state->lifted) return true;
        state->lifted = true;
        return state->throughput.keepPower(mMain.photonPower, sampler);
    }

    // Emission: a source ∝ power and a photon from it, of the stream photon `index` is in.
    // False when it emits nothing.
    bool emit(uint64_t index, Sampler& sampler, PhotonWalk& walk, PhotonPath* path,
              PhotonState* state) const {
        state->causticStream = index >= mMainCount;
        const PhotonStream& stream = state->causticStream ? mCaustic : mMain;
        const size_t source = stream.chooser.choose(sampler.get1D());
        PhotonEmission em;
        // Light from a medium is never direct light of the render pass (no NEE to media): its
        // first scattering and its first diffuse surface are stored, in the global map.
        const bool fromMedium = source >= mSources.lights.size();
        if (state->causticStream) {
            if (!mSources.projection.maps[source]->emit(sampler, &em)) return false;
            path->light = uint32_t(source);
        } else if (fromMedium) {
            const size_t e = source - mSources.lights.size();
            path->fromMedium = true;
            if (!mSources.emitters[e].sample(
                    sampler, walk.tracking().context(mSources.emitterMedium[e]), &em))
                return false;
        } else if (!mSources.lights[source]->emitPhoton(mSources.bounds, sampler, &em)) {
            return false;
        } else {
            path->light = uint32_t(source);
        }
        state->projected = !fromMedium && mSources.projection.maps[source];
        const float power = stream.photonPower * em.weight;
        if (!std::isfinite(power)) path->nonFinite = true;
        if (!(power > 0.f) || path->nonFinite) return false;
        if (!state->causticStream) path->power = power;
        walk.setWavelength(em.lambda);
        state->ray = Ray{em.origin, em.direction, kInfinity};
        state->throughput.beta = SampledSpectrum(power);
        state->direct = state->specularOnly = !fromMedium;
        return true;
    }

    // One free flight from state.ray: straight, or along its Fermat path where light curves. *hit
    // is the surface the flight ended at, if any; state.ray becomes the ray that met it (a curved
    // flight's last chord) or, for a curved flight that ran out of path, the straight ray on.
    FlightEvent fly(Sampler& sampler, PhotonWalk& walk, PhotonState* state, PhotonPath* path,
                    std::optional<SurfaceHit>* hit) const {
        Ray& ray = state->ray;
        if (mSettings.field) {
            // The curved flight; the surface hit of the chord it ended on, if any, is kept.
            const CurvedWalk curved{*mSettings.field, mSettings.curvedPath, mSettings.curvedMaxArc,
                                    [&](const Ray& chord, float tMax) {
                                        if (!mGeometry) return kInfinity;
                                        *hit = mGeometry->intersect(Ray{chord.o, chord.d, tMax});
                                        return *hit ? (*hit)->t : kInfinity;
                                    }};
            CurvedWalkEnd end;
            FlightEvent ev = walk.flyCurved(curved, ray, sampler, &end);
            if (end.kind == CurvedWalkEnd::Kind::Surface) {
                ray = Ray{end.chord.o, end.chord.d, kInfinity};
                return ev;
            }
            if (ev.end != FlightEnd::Escaped) {
                hit->reset();
                return ev;
            }
            // Beyond curvedMaxArc of path, or at the stepper's hard cap on ODE steps
            // (CurvedPathSettings::maxSteps, counted as a capped path: the rest of the flight is
            // straight, a bias): straight on from where the path got to.
            if (end.kind == CurvedWalkEnd::Kind::Capped) path->capped = true;
            ray = Ray{end.p, end.direction, kInfinity};
        }
        hit->reset();
        if (mGeometry) *hit = mGeometry->intersect(ray);
        return walk.fly(ray, *hit ? (*hit)->t : kInfinity, sampler);
    }

    // A photon at a surface: stored where it is diffuse (not straight from a light, whose direct
    // light the render pass computes, unless paths curve), then reflected or refracted
    // (continueAtSurface) with the roulette that keeps its power. False when the walk ends.
    bool atSurface(const SurfaceHit& hit, Sampler& sampler, PhotonWalk& walk, PhotonState* state,
                   PhotonPath* path, PhotonMapLists* out) const {
        const Material& mat = mGeometry->materialAt(hit);
        const float power = state->throughput.beta[0];
        if (!mat.specular()) {
            // Where paths curve there are no shadow rays: the first diffuse hit is stored too.
            if (!state->direct || (mSettings.field && mSettings.storeFirstInteraction)) {
                PhotonList* list = !state->direct && state->specularOnly ? &out->surfaceCaustic
                                                                         : &out->surfaceGlobal;
                if (!storePhoton(Photon{hit.p, state->ray.d, walk.wavelength(), power}, walk, list,
                                 path))
                    return false;
            }
            state->specularOnly = false;
        }
        if (!continueAtSurface(mat, hit, walk.tracking().wavelengths(), TransportMode::Importance,
                               sampler, state))
            return false;
        path->nonFinite = !std::isfinite(state->throughput.beta[0]);
        if (path->nonFinite || !state->throughput.keepPower(power, sampler)) return false;
        state->direct = false;
        return true;
    }

    // A photon scattered (or re-emitted) in a medium: stored unless it is the first interaction
    // of light straight from a light, which the render pass computes itself. A fluorescent
    // re-emission is stored always (no render pass computes light that changes wavelength by
    // shadow rays), at the new wavelength with the power after re-emission, Φ λi/λo
    // (photon_walk.h), flagged by its absorbed λi so that the estimates give it the isotropic lobe
    // of re-emission. False when the walk ends.
    bool inMedium(const FlightEvent& ev, PhotonWalk& walk, PhotonState* state, PhotonPath* path,
                  PhotonMapLists* out) const {
        const float power = state->throughput.beta[0];
        const bool reemitted = ev.end == FlightEnd::Reemitted;
        if (reemitted || !state->direct || mSettings.storeFirstInteraction) {
            const Photon ph =
                reemitted ? Photon{ev.p, ev.wi, ev.lambdaOut, power * ev.weight, ev.lambdaIn}
                          : Photon{ev.p, ev.wi, walk.wavelength(), power};
            if (!storePhoton(ph, walk, &out->volume, path)) return false;
        }
        state->direct = false;
        state->specularOnly = false;
        state->throughput.beta *= ev.weight;
        path->nonFinite = !std::isfinite(state->throughput.beta[0]);
        if (!(state->throughput.beta[0] > 0.f) || path->nonFinite) return false;
        state->ray = Ray{ev.p, ev.wo, kInfinity};
        return true;
    }

    const PhotonSources& mSources;
    const PhotonStream& mMain;
    const PhotonStream& mCaustic;
    uint64_t mMainCount;
    const PhotonPassSettings& mSettings;
    const GeometryScene* mGeometry;
};

}  // namespace

bool projectionWanted(const PhotonPassSettings& settings) {
    return settings.projection == PhotonPassSettings::Projection::On && !settings.field;
}

void PhotonPassStats::add(const PhotonPassStats& pass) {
    emitted += pass.emitted;
    stored += pass.stored;
    cappedPaths += pass.cappedPaths;
    nonFinite += pass.nonFinite;
    fromMedia += pass.fromMedia;
    mediumPower = pass.mediumPower;
    emittedPower += pass.emittedPower;
    seconds += pass.seconds;
    interrupted = interrupted || pass.interrupted;
}

PhotonList tracePhotons(const std::vector<const Light*>& lights,
                        const std::vector<const Medium*>& media, const PhotonPassSettings& settings,
                        PhotonPassStats* stats) {
    return tracePhotonMaps(lights, media, nullptr, settings, stats).volume;
}

PhotonMapLists tracePhotonMaps(const std::vector<const Light*>& lights,
                               const std::vector<const Medium*>& media,
                               const GeometryScene* geometry, const PhotonPassSettings& settings,
                               PhotonPassStats* stats) {
    const Clock::time_point start = Clock::now();
    PhotonPassStats local;
    PhotonMapLists maps;
    if (geometry && geometry->empty()) geometry = nullptr;

    Bounds3 bounds;
    for (const Medium* m : media) bounds.expand(m->worldBounds());
    if (geometry) bounds.expand(geometry->bounds());
    // Projection maps: not where light curves (straight-line cones and discs).
    const PhotonSources sources(
        lights, media, bounds,
        planProjection(lights, geometry, bounds, projectionWanted(settings)));
    local.mediumPower = sources.mediumPower;
    const LightChooser chooser(sources.powers());
    // Curved flights: the step cap near surfaces (surface_step_cap.h), so that a photon's hit
    // on a surface it meets at a shallow angle, or grazes, is its path's.
    PhotonPassSettings curved = settings;
    if (settings.field && geometry && settings.curvedPath.capNearSurfaces) {
        curved.curvedPath.stepCap = surfaceStepCap(
            settings.field.get(), settings.curvedPath.tolerance,
            [geometry](const Vec3d& o, const Vec3d& d) { return geometry->surfaceDistance(o, d); });
    }
    const uint64_t n = settings.photons;
    // Nothing to do without photons, light, media or surfaces: a photon that meets nothing
    // stores nothing.
    if (n > 0 && (!media.empty() || geometry) && chooser.totalPower() > 0.0) {
        const PhotonStream main{chooser, float(chooser.totalPower() / double(n))};
        const uint64_t nCaustic = sources.projection.any() ? settings.causticPhotonsOrDefault() : 0;
        const LightChooser causticChooser(sources.projectedPowers());
        const PhotonStream caustic{causticChooser, float(causticChooser.totalPower() /
                                                         double(std::max<uint64_t>(nCaustic, 1)))};
        const uint64_t total = n + nCaustic;
        const uint64_t blocks = photonBlockCount(total);
        std::vector<PhotonMapLists> blockPhotons(blocks);
        std::vector<uint64_t> blockCapped(blocks, 0), blockFromMedia(blocks, 0),
            blockNonFinite(blocks, 0);
        std::vector<double> blockPower(blocks, 0.0);
        Progress progress("photons", total, "photons", settings.progress);
        const PhotonTracer tracer(sources, main, caustic, n, curved, geometry);

        forEachPhotonBlock(total, media, progress, /*stopOnInterrupt=*/true,
                           [&](PhotonWalk& walk, uint64_t b, uint64_t first, uint64_t last) {
                               for (uint64_t i = first; i < last; ++i) {
                                   const uint64_t flightsCut = walk.tracking().cappedFlights;
                                   const PhotonPath path = tracer.trace(i, walk, &blockPhotons[b]);
                                   // A flight cut at the collision cap (tracking.h) caps the path
                                   // too.
                                   blockCapped[b] +=
                                       path.capped || walk.tracking().cappedFlights != flightsCut;
                                   blockNonFinite[b] += path.nonFinite;
                                   blockFromMedia[b] += path.fromMedium;
                                   blockPower[b] += path.power;
                               }
                           });
        progress.finish();

        // Concatenated in block order: the lists are the same for any thread count.
        auto concatenate = [&](PhotonList PhotonMapLists::*member) {
            size_t count = 0;
            for (const auto& bp : blockPhotons) count += (bp.*member).size();
            PhotonList& all = maps.*member;
            all.reserve(count);
            for (auto& bp : blockPhotons) {
                all.insert(all.end(), (bp.*member).begin(), (bp.*member).end());
                PhotonList().swap(bp.*member);
            }
        };
        concatenate(&PhotonMapLists::volume);
        concatenate(&PhotonMapLists::surfaceGlobal);
        concatenate(&PhotonMapLists::surfaceCaustic);
        for (uint64_t b = 0; b < blocks; ++b) {
            local.cappedPaths += blockCapped[b];
            local.fromMedia += blockFromMedia[b];
            local.emittedPower += blockPower[b];
            local.nonFinite += blockNonFinite[b];
        }
        local.emitted = total;
        local.interrupted = interruptRequested();
    }
    local.stored = maps.volume.size() + maps.surfaceGlobal.size() + maps.surfaceCaustic.size();
    local.seconds = secondsSince(start);
    if (stats) *stats = local;
    return maps;
}

}  // namespace mirage
