// The photon pass: emission ∝ power, flights by photon_walk, stored scattering events.
//
// Power bookkeeping. A light l of power Φ_l is chosen with probability Φ_l/Φ (Φ = Σ Φ_l) and
// emits with the light's own PhotonEmission::weight w (mean 1), so a photon carries
// Φ_l / (N Φ_l/Φ) × w = (Φ/N) w watts: every photon of every light starts with the same
// power when the lights sample their emission exactly. The albedo roulette keeps that power
// through the walk (photon_walk.h); only a spectral phase mixture could change it, by p/pdf,
// and a fluorescent re-emission, by λi/λo (energy: Γ counts photons, Mobley 1994 §5.13).
//
// Not yet emitted: photons from emissive media (fire), which would leave the grid ∝ σa·Le.
#include "photon/photon_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "photon/photon_walk.h"

namespace mirage {

namespace {

// Photons per block: the unit of parallel work and of ordering. Large enough that a block
// (hundreds of microseconds at least) hides the scheduling and the PhotonWalk set-up.
constexpr uint64_t kBlockPhotons = 4096;

// Light choice ∝ emitted power: a discrete distribution by its cumulative sum.
class LightChooser {
public:
    LightChooser(const std::vector<const Light*>& lights, const Bounds3& bounds) {
        double sum = 0.0;
        for (const Light* l : lights) {
            sum += std::max(0.0, double(l->emittedPower(bounds)));
            mCdf.push_back(sum);
        }
        mTotal = sum;
    }
    double totalPower() const { return mTotal; }
    // Index of the light for u in [0, 1); lights of zero power are never chosen.
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
};

// Photon `index`: emission, then flights until it leaves every medium, is absorbed, or has
// scattered maxBounces times. Appends its stored photons to *out.
PhotonPath tracePhoton(uint64_t index, const std::vector<const Light*>& lights,
                       const LightChooser& chooser, const Bounds3& bounds, float photonPower,
                       const PhotonPassSettings& settings, const GeometryScene* geometry,
                       PhotonWalk& walk, PhotonMapLists* out) {
    PhotonPath path;
    Sampler sampler(settings.seed, index, 0);
    const Light& light = *lights[chooser.choose(sampler.get1D())];
    PhotonEmission em;
    if (!light.emitPhoton(bounds, sampler, &em)) return path;
    float power = photonPower * em.weight;
    if (!(power > 0.f)) return path;
    walk.setWavelength(em.lambda);

    Ray ray{em.origin, em.direction, kInfinity};
    bool direct = true;        // no interaction yet: light straight from the light
    bool specularOnly = true;  // every interaction so far was a mirror or glass
    for (int bounces = 0;;) {
        std::optional<SurfaceHit> hit;
        if (geometry) hit = geometry->intersect(ray);
        FlightEvent ev = walk.fly(ray, hit ? hit->t : kInfinity, sampler);
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
                if (!direct)
                    (specularOnly ? out->surfaceCaustic : out->surfaceGlobal)
                        .push_back(Photon{hit->p, ray.d, walk.wavelength(), power});
                // Albedo roulette: bounce with probability ρ(λ), power unchanged (f cos/pdf = ρ).
                if (sampler.get1D() >= mat.albedo(walk.wavelength())) return path;
                wiL = sampleCosineHemisphere(sampler.get1D(), sampler.get1D());
                if (woL.z < 0.f) wiL.z = -wiL.z;
                specularOnly = false;
            }
            direct = false;
            if (!(power > 0.f)) return path;
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
        if (ev.end == FlightEnd::Reemitted) {
            out->volume.push_back(
                Photon{ev.p, ev.wi, ev.lambdaOut, power * ev.weight, ev.lambdaIn});
        } else if (!direct || settings.storeFirstInteraction) {
            out->volume.push_back(Photon{ev.p, ev.wi, walk.wavelength(), power});
        }
        direct = false;
        specularOnly = false;
        ++bounces;
        power *= ev.weight;
        if (!(power > 0.f)) return path;
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
    LightChooser chooser(lights, bounds);
    const uint64_t n = settings.photons;
    // Nothing to do without photons, light, media or surfaces: a photon that meets nothing
    // stores nothing.
    if (n > 0 && (!media.empty() || geometry) && chooser.totalPower() > 0.0) {
        const float photonPower = float(chooser.totalPower() / double(n));
        const uint64_t blocks = (n + kBlockPhotons - 1) / kBlockPhotons;
        std::vector<PhotonMapLists> blockPhotons(blocks);
        std::vector<uint64_t> blockCapped(blocks, 0);
        Progress progress("photons", n, "photons", settings.progress);

        tbb::parallel_for(
            tbb::blocked_range<uint64_t>(0, blocks, 1), [&](const tbb::blocked_range<uint64_t>& r) {
                PhotonWalk walk(media);
                for (uint64_t b = r.begin(); b != r.end(); ++b) {
                    uint64_t first = b * kBlockPhotons, last = std::min(n, first + kBlockPhotons);
                    for (uint64_t i = first; i < last; ++i) {
                        PhotonPath path = tracePhoton(i, lights, chooser, bounds, photonPower,
                                                      settings, geometry, walk, &blockPhotons[b]);
                        blockCapped[b] += path.capped;
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
        for (uint64_t b = 0; b < blocks; ++b) local.cappedPaths += blockCapped[b];
        local.emitted = n;
    }
    local.stored = maps.volume.size() + maps.surfaceGlobal.size() + maps.surfaceCaustic.size();
    local.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (stats) *stats = local;
    return maps;
}

}  // namespace mirage
