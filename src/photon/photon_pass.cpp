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

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "core/interrupt.h"
#include "core/sampling.h"
#include "photon/medium_emitter.h"
#include "photon/photon_walk.h"
#include "transport/surface_step_cap.h"

namespace mirage {

namespace {

// Photons per block: the unit of parallel work and of ordering. Large enough that a block
// (hundreds of microseconds at least) hides the scheduling and the PhotonWalk set-up.
constexpr uint64_t kBlockPhotons = 4096;

// Source choice ∝ emitted power: a discrete distribution by its cumulative sum over the
// lights, then the emissive media (index lights.size() + e is emitter e).
class LightChooser {
public:
    LightChooser(const std::vector<const Light*>& lights, const Bounds3& bounds,
                 const std::vector<MediumEmitter>& emitters) {
        double sum = 0.0;
        for (const Light* l : lights) {
            sum += std::max(0.0, double(l->emittedPower(bounds)));
            mCdf.push_back(sum);
        }
        for (const MediumEmitter& e : emitters) {
            sum += e.tablePower();
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
    bool fromMedium = false;  // emitted by an emissive medium
    double power = 0.0;       // W the photon left its source with
    bool nonFinite = false;  // a photon with non-finite power or position was dropped
};

// A photon reaches a map only if everything an estimate reads from it is finite: one NaN or ∞
// power would poison every estimate whose search finds it. The path ends at such a photon.
bool finitePhoton(const Photon& ph) {
    return std::isfinite(ph.power) && isFinite(ph.p) && isFinite(ph.wi) && std::isfinite(ph.lambda);
}

// Photon `index`: emission, then flights until it leaves every medium, is absorbed, or has
// scattered maxBounces times. Appends its stored photons to *out.
PhotonPath tracePhoton(uint64_t index, const std::vector<const Light*>& lights,
                       const std::vector<MediumEmitter>& emitters,
                       const std::vector<size_t>& emitterMedium, const LightChooser& chooser,
                       const Bounds3& bounds, float photonPower,
                       const PhotonPassSettings& settings, const GeometryScene* geometry,
                       PhotonWalk& walk, PhotonMapLists* out) {
    PhotonPath path;
    Sampler sampler(settings.seed, index, 0);
    const size_t source = chooser.choose(sampler.get1D());
    PhotonEmission em;
    // Light from a medium is never direct light of the render pass (no NEE to media): its
    // first scattering and its first diffuse surface are stored, in the global map.
    const bool fromMedium = source >= lights.size();
    if (fromMedium) {
        const size_t e = source - lights.size();
        path.fromMedium = true;
        if (!emitters[e].sample(sampler, walk.tracking().context(emitterMedium[e]), &em))
            return path;
    } else if (!lights[source]->emitPhoton(bounds, sampler, &em)) {
        return path;
    }
    float power = photonPower * em.weight;
    if (!std::isfinite(power)) path.nonFinite = true;
    if (!(power > 0.f) || path.nonFinite) return path;
    path.power = power;
    walk.setWavelength(em.lambda);

    Ray ray{em.origin, em.direction, kInfinity};
    bool direct = !fromMedium;        // no interaction yet: light straight from the light
    bool specularOnly = !fromMedium;  // every interaction so far was a mirror or glass
    for (int bounces = 0;;) {
        std::optional<SurfaceHit> hit;
        FlightEvent ev;
        bool straight = true;
        if (settings.field) {
            // The curved flight; the surface hit of the chord it ended on, if any, is kept.
            ChordSurfaceTest surfaces = [&](const Ray& chord, float tMax) {
                if (!geometry) return kInfinity;
                hit = geometry->intersect(Ray{chord.o, chord.d, tMax});
                return hit ? hit->t : kInfinity;
            };
            CurvedWalkEnd end;
            ev = walk.flyCurved(*settings.field, settings.curvedPath, surfaces, ray.o, ray.d,
                                settings.curvedMaxArc, sampler, &end);
            if (end.kind == CurvedWalkEnd::Kind::Surface) {
                ray = Ray{end.chord.o, end.chord.d, kInfinity};
                straight = false;
            } else if (ev.end != FlightEnd::Escaped) {
                hit.reset();
                straight = false;
            } else {
                // Beyond curvedMaxArc of path, or at the stepper's hard cap on ODE steps
                // (CurvedPathSettings::maxSteps, counted as a capped path: the rest of the
                // flight is straight, a bias): straight on from where the path got to.
                if (end.kind == CurvedWalkEnd::Kind::Capped) path.capped = true;
                ray = Ray{end.p, end.direction, kInfinity};
            }
        }
        if (straight) {
            hit.reset();
            if (geometry) hit = geometry->intersect(ray);
            ev = walk.fly(ray, hit ? hit->t : kInfinity, sampler);
        }
        if (ev.end == FlightEnd::Escaped && hit) {
            // A surface: reflect, refract or store and bounce.
            const Material& mat = geometry->materialAt(*hit);
            Frame frame(hit->ns);
            Vec3 woL = frame.toLocal(-ray.d);
            Vec3 wiL;
            if (mat.specular()) {
                BsdfSample bs;
                float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
                if (!mat.sample(woL, uc, u1, u2, walk.tracking().wavelengths(),
                                TransportMode::Importance, &bs))
                    return path;
                power *= bs.weight[0];
                wiL = bs.wi;
            } else {
                // Where paths curve there are no shadow rays: the first diffuse hit is stored too.
                if (!direct || (settings.field && settings.storeFirstInteraction)) {
                    Photon ph{hit->p, ray.d, walk.wavelength(), power};
                    if (!finitePhoton(ph)) {
                        path.nonFinite = true;
                        return path;
                    }
                    (!direct && specularOnly ? out->surfaceCaustic : out->surfaceGlobal)
                        .push_back(ph);
                }
                // Albedo roulette: bounce with probability ρ(λ), power unchanged (f cos/pdf = ρ).
                if (sampler.get1D() >= mat.albedo(walk.wavelength())) return path;
                wiL = sampleCosineHemisphere(sampler.get1D(), sampler.get1D());
                if (woL.z < 0.f) wiL.z = -wiL.z;
                specularOnly = false;
            }
            direct = false;
            path.nonFinite = !std::isfinite(power);
            if (!(power > 0.f) || path.nonFinite) return path;
            if (++bounces >= settings.maxBounces) {
                path.capped = true;
                return path;
            }
            ray = spawnRay(*hit, frame.toWorld(wiL));
            continue;
        }
        if (ev.end != FlightEnd::Scattered && ev.end != FlightEnd::Reemitted) return path;
        // The first interaction is direct light; the render pass may compute it itself.
        // A fluorescent re-emission is stored always, first interaction or not (no render
        // pass computes light that changes wavelength by shadow rays), at the new wavelength
        // with the power after re-emission, Φ λi/λo (photon_walk.h), flagged by its absorbed
        // λi so that the estimates give it the isotropic lobe of re-emission.
        const bool reemitted = ev.end == FlightEnd::Reemitted;
        if (reemitted || !direct || settings.storeFirstInteraction) {
            Photon ph = reemitted ? Photon{ev.p, ev.wi, ev.lambdaOut, power * ev.weight, ev.lambdaIn}
                                  : Photon{ev.p, ev.wi, walk.wavelength(), power};
            if (!finitePhoton(ph)) {
                path.nonFinite = true;
                return path;
            }
            out->volume.push_back(ph);
        }
        direct = false;
        specularOnly = false;
        ++bounces;
        power *= ev.weight;
        path.nonFinite = !std::isfinite(power);
        if (!(power > 0.f) || path.nonFinite) return path;
        if (bounces >= settings.maxBounces) {
            path.capped = true;
            return path;
        }
        ray = Ray{ev.p, ev.wo, kInfinity};
    }
}

}  // namespace

PhotonList tracePhotons(const std::vector<const Light*>& lights,
                        const std::vector<const Medium*>& media, const PhotonPassSettings& settings,
                        PhotonPassStats* stats) {
    return tracePhotonMaps(lights, media, nullptr, settings, stats).volume;
}

PhotonMapLists tracePhotonMaps(const std::vector<const Light*>& lights,
                               const std::vector<const Medium*>& media,
                               const GeometryScene* geometry, const PhotonPassSettings& settings,
                               PhotonPassStats* stats) {
    auto start = std::chrono::steady_clock::now();
    PhotonPassStats local;
    PhotonMapLists maps;
    if (geometry && geometry->empty()) geometry = nullptr;

    Bounds3 bounds;
    for (const Medium* m : media) bounds.expand(m->worldBounds());
    if (geometry) bounds.expand(geometry->bounds());
    std::vector<MediumEmitter> emitters;
    std::vector<size_t> emitterMedium;  // index of each emitter's medium in `media`
    for (size_t i = 0; i < media.size(); ++i)
        if (media[i]->emissive() && !media[i]->homogeneous()) {
            emitters.emplace_back(*media[i]);
            emitterMedium.push_back(i);
            local.mediumPower += emitters.back().tablePower();
        }
    LightChooser chooser(lights, bounds, emitters);
    // Curved flights: the step cap near surfaces (surface_step_cap.h), so that a photon's hit
    // on a surface it meets at a shallow angle, or grazes, is its path's.
    PhotonPassSettings curved = settings;
    if (settings.field && geometry && settings.curvedPath.capNearSurfaces) {
        curved.curvedPath.stepCap =
            surfaceStepCap(settings.field, settings.curvedPath.tolerance,
                           [geometry](const Vec3d& o, const Vec3d& d) {
                               return geometry->surfaceDistance(o, d);
                           });
    }
    const uint64_t n = settings.photons;
    // Nothing to do without photons, light, media or surfaces: a photon that meets nothing
    // stores nothing.
    if (n > 0 && (!media.empty() || geometry) && chooser.totalPower() > 0.0) {
        const float photonPower = float(chooser.totalPower() / double(n));
        const uint64_t blocks = (n + kBlockPhotons - 1) / kBlockPhotons;
        std::vector<PhotonMapLists> blockPhotons(blocks);
        std::vector<uint64_t> blockCapped(blocks, 0), blockFromMedia(blocks, 0),
            blockNonFinite(blocks, 0);
        std::vector<double> blockPower(blocks, 0.0);
        Progress progress("photons", n, "photons", settings.progress);

        tbb::parallel_for(
            tbb::blocked_range<uint64_t>(0, blocks, 1), [&](const tbb::blocked_range<uint64_t>& r) {
                PhotonWalk walk(media);
                for (uint64_t b = r.begin(); b != r.end(); ++b) {
                    // Ctrl-C or SIGTERM during a long pass: the remaining blocks are skipped
                    // (one block is a few ms of work), so the process exits promptly.
                    if (interruptRequested()) continue;
                    uint64_t first = b * kBlockPhotons, last = std::min(n, first + kBlockPhotons);
                    for (uint64_t i = first; i < last; ++i) {
                        uint64_t flightsCut = walk.tracking().cappedFlights;
                        PhotonPath path =
                            tracePhoton(i, lights, emitters, emitterMedium, chooser, bounds,
                                        photonPower, curved, geometry, walk, &blockPhotons[b]);
                        // A flight cut at the collision cap (tracking.h) caps the path too.
                        blockCapped[b] +=
                            path.capped || walk.tracking().cappedFlights != flightsCut;
                        blockNonFinite[b] += path.nonFinite;
                        blockFromMedia[b] += path.fromMedium;
                        blockPower[b] += path.power;
                    }
                    progress.advance(last - first);
                }
            });
        progress.finish();

        // Concatenated in block order: the lists are the same for any thread count.
        auto concatenate = [&](PhotonList PhotonMapLists::*member) {
            size_t total = 0;
            for (const auto& bp : blockPhotons) total += (bp.*member).size();
            PhotonList& all = maps.*member;
            all.reserve(total);
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
        local.emitted = n;
        local.interrupted = interruptRequested();
    }
    local.stored = maps.volume.size() + maps.surfaceGlobal.size() + maps.surfaceCaustic.size();
    local.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (stats) *stats = local;
    return maps;
}

}  // namespace mirage
