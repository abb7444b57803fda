// The photon pass: emission ∝ power, flights by photon_walk, stored scattering events.
//
// Power bookkeeping. A light l of power Φ_l is chosen with probability Φ_l/Φ (Φ = Σ Φ_l) and
// emits with the light's own PhotonEmission::weight w (mean 1), so a photon carries
// Φ_l / (N Φ_l/Φ) × w = (Φ/N) w watts: every photon of every light starts with the same
// power when the lights sample their emission exactly. The albedo roulette keeps that power
// through the walk (photon_walk.h); only a spectral phase mixture could change it, by p/pdf.
//
// Not yet emitted: photons from emissive media (fire), which would leave the grid ∝ σa·Le.
#include "photon/photon_pass.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

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
                       const PhotonPassSettings& settings, PhotonWalk& walk, PhotonList* out) {
    PhotonPath path;
    Sampler sampler(settings.seed, index, 0);
    const Light& light = *lights[chooser.choose(sampler.get1D())];
    PhotonEmission em;
    if (!light.emitPhoton(bounds, sampler, &em)) return path;
    float power = photonPower * em.weight;
    if (!(power > 0.f)) return path;
    walk.setWavelength(em.lambda);

    Ray ray{em.origin, em.direction, kInfinity};
    for (int bounces = 0;;) {
        FlightEvent ev = walk.fly(ray, kInfinity, sampler);
        if (ev.end != FlightEnd::Scattered) return path;
        // The first interaction is direct light; the render pass may compute it itself.
        if (bounces > 0 || settings.storeFirstInteraction)
            out->push_back(Photon{ev.p, ev.wi, em.lambda, power});
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
    auto start = std::chrono::steady_clock::now();
    PhotonPassStats local;
    PhotonList photons;

    Bounds3 bounds;
    for (const Medium* m : media) bounds.expand(m->worldBounds());
    LightChooser chooser(lights, bounds);
    const uint64_t n = settings.photons;
    // Nothing to do without photons, light or media: photons that meet no medium store nothing.
    if (n > 0 && !media.empty() && chooser.totalPower() > 0.0) {
        const float photonPower = float(chooser.totalPower() / double(n));
        const uint64_t blocks = (n + kBlockPhotons - 1) / kBlockPhotons;
        std::vector<PhotonList> blockPhotons(blocks);
        std::vector<uint64_t> blockCapped(blocks, 0);
        Progress progress("photons", n, "photons", settings.progress);

        tbb::parallel_for(
            tbb::blocked_range<uint64_t>(0, blocks, 1), [&](const tbb::blocked_range<uint64_t>& r) {
                PhotonWalk walk(media);
                for (uint64_t b = r.begin(); b != r.end(); ++b) {
                    uint64_t first = b * kBlockPhotons, last = std::min(n, first + kBlockPhotons);
                    for (uint64_t i = first; i < last; ++i) {
                        PhotonPath path = tracePhoton(i, lights, chooser, bounds, photonPower,
                                                      settings, walk, &blockPhotons[b]);
                        blockCapped[b] += path.capped;
                    }
                    progress.advance(last - first);
                }
            });
        progress.finish();

        // Concatenated in block order: the list is the same for any thread count.
        size_t total = 0;
        for (const auto& bp : blockPhotons) total += bp.size();
        photons.reserve(total);
        for (uint64_t b = 0; b < blocks; ++b) {
            photons.insert(photons.end(), blockPhotons[b].begin(), blockPhotons[b].end());
            PhotonList().swap(blockPhotons[b]);
            local.cappedPaths += blockCapped[b];
        }
        local.emitted = n;
    }
    local.stored = photons.size();
    local.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (stats) *stats = local;
    return photons;
}

}  // namespace mirage
