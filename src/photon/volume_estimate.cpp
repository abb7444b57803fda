#include "photon/volume_estimate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "core/error.h"
#include "spectrum/cie.h"

namespace mirage {

ScatteringProbe::ScatteringProbe(const std::vector<const Medium*>& media) : mMedia(media) {
    for (const Medium* m : media) {
        mContexts.emplace_back(*m);
        for (const MediumComponent& c : m->shader().components) mGrey &= c.sigmaS.isConstant();
        mGrey &= !m->fluorescent();
    }
    mSigmaA.resize(kMaxComponents);
}

float ScatteringProbe::sigmaS(const Vec3& worldP, float lambdaNm) {
    float sigmaS = 0.f;
    for (size_t i = 0; i < mMedia.size(); ++i) {
        Vec3 p = mContexts[i].pointToObject(worldP);
        if (!mMedia[i]->objectBounds().contains(p)) continue;
        sigmaS += mMedia[i]->sigmaSAt(p, mContexts[i], lambdaNm);
    }
    return sigmaS;
}

float ScatteringProbe::reemissionDensity(const Vec3& worldP, float lambdaInNm) {
    float density = 0.f;
    for (size_t i = 0; i < mMedia.size(); ++i) {
        const Medium& m = *mMedia[i];
        if (!m.fluorescent()) continue;
        Vec3 p = mContexts[i].pointToObject(worldP);
        if (!m.objectBounds().contains(p)) continue;
        m.sigmaAComponentsAt(p, mContexts[i], lambdaInNm, mSigmaA.data());
        const auto& comps = m.shader().components;
        for (size_t c = 0; c < comps.size(); ++c)
            if (comps[c].fluorescent()) density += comps[c].quantumEfficiency * mSigmaA[c];
    }
    return density;
}

VolumePhotons::VolumePhotons(PhotonList photons, const std::vector<const Medium*>& media,
                             const std::vector<Vec3>& xyzPerWatt)
    : mMap(std::move(photons)), mMedia(media) {
    const size_t n = mMap.size();
    mFluxXyz.resize(n);
    for (size_t i = 0; i < n; ++i) {
        // An achromatic scene has no emissive media: every photon comes from a light.
        MIRAGE_CHECK(xyzPerWatt.empty() || mMap[i].light < xyzPerWatt.size());
        mFluxXyz[i] = xyzPerWatt.empty() ? cieXyz(mMap[i].lambda) * (mMap[i].power / kCieYIntegral)
                                         : xyzPerWatt[mMap[i].light] * mMap[i].power;
    }
    mSigmaS.resize(n);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024),
                      [&](const tbb::blocked_range<size_t>& r) {
                          ScatteringProbe probe(media);
                          for (size_t i = r.begin(); i < r.end(); ++i) {
                              // The density of its event where and when it happened.
                              probe.setTimeOffset(mMap[i].time);
                              mSigmaS[i] = probe.eventDensity(mMap[i].p, mMap[i]);
                          }
                      });

    // The lobes of every component of every medium, in order. One lobe, or lobes that are all
    // the same, need no per-photon weights.
    for (const Medium* m : media)
        for (const MediumComponent& c : m->shader().components)
            mLobes.emplace_back(c.phase, c.g, c.g2, c.phaseWeight);
    bool same = true;
    for (const ComponentPhase& l : mLobes) same &= l == mLobes.front();
    if (mLobes.empty()) mLobes.emplace_back();
    if (same) {
        mLobes.resize(1);
        return;
    }

    // Mixture weights σs,c(x_p, λ_p) / Σ σs at each photon, all 4 path wavelengths set to λ_p.
    const size_t L = mLobes.size();
    mLobeWeights.assign(n * L, 0.f);
    auto weigh = [&](const tbb::blocked_range<size_t>& r) {
        std::vector<Medium::Context> contexts;
        for (const Medium* m : media) contexts.emplace_back(*m);
        for (size_t i = r.begin(); i < r.end(); ++i) {
            if (mMap[i].reemitted()) continue;  // isotropic: phase() needs no weights
            SampledWavelengths w;
            w.lambda.fill(mMap[i].lambda);
            w.pdf.fill(1.f);
            float* weights = &mLobeWeights[i * L];
            size_t lobe = 0;
            float total = 0.f;
            for (size_t mi = 0; mi < media.size(); ++mi) {
                const Medium& m = *media[mi];
                const int components = int(m.shader().components.size());
                // Outside its box a medium has no particles (its homogeneous components would
                // still report their constant).
                contexts[mi].setTimeOffset(mMap[i].time);
                Vec3 p = contexts[mi].pointToObject(mMap[i].p);
                if (!m.objectBounds().contains(p)) {
                    lobe += size_t(components);
                    continue;
                }
                contexts[mi].setWavelengths(w);
                MediumPoint mp;
                m.eval(p, contexts[mi], &mp);
                for (int c = 0; c < components; ++c, ++lobe) {
                    weights[lobe] = mp.sigmaSComponent[size_t(c)][0];
                    total += weights[lobe];
                }
            }
            // A photon stored where no component scatters can only come from rounding at a
            // medium's edge: give it the plain average of the lobes.
            for (size_t l = 0; l < L; ++l)
                weights[l] = total > 0.f ? weights[l] / total : 1.f / float(L);
        }
    };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 256), weigh);
}

float VolumePhotons::phase(size_t slot, const Vec3& wo) const {
    if (mMap[slot].reemitted()) return kInv4Pi;
    float cosTheta = dot(mMap[slot].wi, wo);
    if (mLobeWeights.empty()) return mLobes[0].eval(cosTheta);
    const size_t L = mLobes.size();
    const float* weights = &mLobeWeights[slot * L];
    float p = 0.f;
    for (size_t l = 0; l < L; ++l)
        if (weights[l] > 0.f) p += weights[l] * mLobes[l].eval(cosTheta);
    return p;
}

namespace {

// Σ_k weight(k) p_k fluxXyz_k / ((4/3) π r³) over the k nearest photons to x.
// Each photon's term goes to its light group too (photon_groups.h).
template <typename Weight>
Vec3 gather(const VolumePhotons& photons, const Vec3& x, const Vec3& wo, const PhotonSearch& search,
            const PhotonGroups& groups, Weight&& weight) {
    const int k = search.k;
    const float maxRadius = search.maxRadius;
    const PhotonNeighbour* buffer = search.buffer;
    int found = photons.map().nearest(x, k, maxRadius, search.buffer);
    if (found == 0) return Vec3(0.f);
    // Fewer than k photons: the search sphere was the whole maxRadius ball. k coincident
    // photons would give r = 0; the density there is not resolvable, so the ball is kept at a
    // thousandth of maxRadius.
    float r = found == k ? std::max(std::sqrt(buffer[0].d2), 1e-3f * maxRadius) : maxRadius;
    const float unbias = found == k ? float(k - 1) / float(k) : 1.f;  // see volume_estimate.h
    const float norm = unbias / ((4.f / 3.f) * kPi * r * r * r);
    const PhotonGroups normGroups = groups.scaled(norm);
    Vec3 sum(0.f);
    for (int i = 0; i < found; ++i) {
        uint32_t slot = buffer[i].index;
        const Vec3 term = photons.fluxXyz(slot) * (weight(slot) * photons.phase(slot, wo));
        sum += term;
        normGroups.add(photons.map()[slot], term);
    }
    return sum * norm;
}

}  // namespace

Vec3 pointEstimate(const VolumePhotons& photons, const Vec3& x, const Vec3& wo,
                   const PhotonSearch& search) {
    MIRAGE_CHECK(search.k >= 2);
    return gather(photons, x, wo, search, PhotonGroups(), [](uint32_t) { return 1.f; });
}

Vec3 pointEstimateAlongRay(const VolumePhotons& photons, const Ray& ray,
                           const RayOpticalDepth& depth, const PhotonSearch& search,
                           const PointMarch& march, const ViewWeight& view,
                           const PhotonGroups& groups) {
    MIRAGE_CHECK(search.k >= 2);
    const float step = march.step, u = march.u;
    ScatteringProbe& probe = *march.probe;
    if (depth.empty() || photons.size() == 0 || !(step > 0.f)) return Vec3(0.f);
    probe.setTimeOffset(depth.timeOffset());  // σs along the ray at the ray's time
    const Vec3 wo = -ray.d;
    const PhotonGroups stepGroups = groups.scaled(step);
    Vec3 sum(0.f);
    // Points beyond the last medium's exit are not taken: σs = 0 there, even if photons inside
    // are within reach of the search.
    for (int j = 0;; ++j) {
        float t = depth.tBegin() + (float(j) + u) * step;
        if (!(t < depth.tEnd())) break;
        Vec3 x = ray.at(t);
        float greySigmaS = probe.grey() ? probe.sigmaS(x, 550.f) : 0.f;
        if (probe.grey() && greySigmaS == 0.f) continue;  // nothing in-scatters here
        sum += gather(photons, x, wo, search, stepGroups, [&](uint32_t slot) {
            const Photon& p = photons.map()[slot];
            float atPhoton = photons.sigmaS(slot);
            if (!(atPhoton > 0.f)) return 0.f;
            float here = probe.grey() ? greySigmaS : probe.eventDensity(x, p);
            return depth.transmittance(t, p.lambda) * cappedDensityRatio(here, atPhoton) *
                   view(p.lambda);
        });
    }
    return sum * step;
}

}  // namespace mirage
