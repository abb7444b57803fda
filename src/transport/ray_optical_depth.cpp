#include "transport/ray_optical_depth.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "volume/grid_lookup.h"

namespace mirage {

RayOpticalDepth::MediumInfo::MediumInfo(const Medium* m) : medium(m), context(*m) {}

RayOpticalDepth::RayOpticalDepth(RayOpticalDepth&&) noexcept = default;
RayOpticalDepth& RayOpticalDepth::operator=(RayOpticalDepth&&) noexcept = default;
RayOpticalDepth::~RayOpticalDepth() = default;

RayOpticalDepth::RayOpticalDepth(const std::vector<const Medium*>& media, float stepVoxels)
    : mStepVoxels(stepVoxels) {
    MIRAGE_CHECK(stepVoxels > 0.f);
    std::vector<SpectralComponent> linear, nonLinear;
    for (const Medium* m : media) {
        MediumInfo info(m);
        info.voxel = kInfinity;
        for (const FloatGrid& g : m->binding().grids()) {
            info.accessors.push_back(g.accessor());
            info.voxel = std::min(info.voxel, g.minVoxelSize());
        }
        if (m->binding().grids().empty()) {
            const MajorantGrid& maj = m->majorant();
            Vec3 diag = maj.bounds().diagonal();
            for (int a = 0; a < 3; ++a)
                info.voxel = std::min(info.voxel, diag[a] / float(std::max(maj.res(a), 1)));
        }
        const auto& components = m->shader().components;
        for (int i = 0; i < int(components.size()); ++i) {
            const MediumComponent& c = components[size_t(i)];
            const ComponentModel& model = m->binding().componentModel(i);
            const float k = c.concentration * m->binding().densityScale();
            Term term;
            term.grid = m->binding().componentSlot(i);
            term.scale = k;
            if (model.grey()) {
                float sigmaT = c.sigmaA.constantValue() + c.sigmaS.constantValue();
                // A component that neither absorbs nor scatters adds nothing.
                if (!(sigmaT * k > 0.f)) continue;
                term.scale = k * sigmaT;
                term.channel = 0;
                info.terms.push_back(term);
                continue;
            }
            (model.linear() ? linear : nonLinear).push_back({&model, mChannels});
            for (float power : model.depthPowers()) {
                term.channel = mChannels++;
                term.exponent = power;
                info.terms.push_back(term);
            }
        }
        mMedia.push_back(std::move(info));
    }
    mSpectral = std::move(linear);
    mSpectral.insert(mSpectral.end(), nonLinear.begin(), nonLinear.end());
}

void RayOpticalDepth::march(const Ray& ray, float tMax) {
    MIRAGE_DCHECK(std::abs(length(ray.d) - 1.f) < 1e-3f);
    mSpans.clear();
    mNodes = 0;
    mOpaque = false;
    float t0 = kInfinity, t1 = -kInfinity, h = kInfinity;
    for (size_t i = 0; i < mMedia.size(); ++i) {
        const Medium& m = *mMedia[i].medium;
        Ray objectRay = mMedia[i].context.toObject(ray);
        float a, b;
        if (!m.objectBounds().intersect(objectRay.o, objectRay.d, 0.f, tMax, &a, &b) || !(a < b))
            continue;
        // A medium confined to a region: its chord (convex), or first entry to last exit, where
        // the nodes' midpoints test the region.
        const Confinement& where = m.confinement();
        if (!where.clip(ray, &a, &b) || !(a < b)) continue;
        mSpans.push_back({int(i), objectRay, a, b});
        t0 = std::min(t0, a);
        t1 = std::max(t1, b);
        // The object ray has the world ray's parameter, so one voxel spans voxel/|d_object| in t.
        h = std::min(h, mStepVoxels * mMedia[i].voxel / length(objectRay.d));
        // A non-convex region, and every region cut out, is sampled at the nodes' midpoints:
        // 1/64 of its size apart.
        if (where.region() && !where.region()->convex())
            h = std::min(h, length(where.region()->bounds().diagonal()) / 64.f);
        for (const auto& r : where.excluded())
            h = std::min(h, length(r->bounds().diagonal()) / 64.f);
    }
    if (mSpans.empty() || !(t0 < t1)) {
        mT0 = mT1 = 0.f;
        return;
    }
    mT0 = t0;
    mT1 = t1;
    float nodes = std::ceil((t1 - t0) / h);
    mNodes = !(nodes >= 1.f) ? 1 : (nodes > float(kMaxNodes) ? kMaxNodes : int(nodes));
    mH = (t1 - t0) / float(mNodes);

    const size_t C = size_t(mChannels);
    mTau.assign((size_t(mNodes) + 1) * C, 0.f);
    // Each medium adds its intervals' integrals to mTau[j + 1] (span order, as the sum at a
    // node always was), its invariants held outside the loop over nodes; then one running sum
    // turns the increments into τ. A medium stops once its own grey τ passes kOpaqueDepth: the
    // others only add to it, so the sum is opaque there too.
    for (const Span& s : mSpans) addSpan(ray, s);
    for (int j = 0; j < mNodes; ++j) {
        const float* prev = &mTau[size_t(j) * C];
        float* next = &mTau[size_t(j + 1) * C];
        for (size_t c = 0; c < C; ++c) next[c] += prev[c];
        if (next[0] > kOpaqueDepth && j + 1 < mNodes) {
            mNodes = j + 1;
            mT1 = t0 + float(j + 1) * mH;
            mOpaque = true;
            break;
        }
    }
}

void RayOpticalDepth::addSpan(const Ray& ray, const Span& s) {
    MediumInfo& info = mMedia[size_t(s.medium)];
    const Medium& medium = *info.medium;
    const auto& grids = medium.binding().grids();
    const Confinement& where = medium.confinement();
    const bool testRegion = !where.oneInterval();
    const size_t C = size_t(mChannels);
    // The nodes whose intervals overlap the span.
    const int jBegin = std::max(0, int(std::floor((s.t0 - mT0) / mH)) - 1);
    const int jEnd = std::min(mNodes, int(std::ceil((s.t1 - mT0) / mH)) + 1);
    float greyTau = 0.f;  // this medium's own, a lower bound on the ray's
    for (int j = jBegin; j < jEnd; ++j) {
        const float a = mT0 + float(j) * mH;
        const float b = j + 1 == mNodes ? mT1 : mT0 + float(j + 1) * mH;
        // Midpoint rule on the part of the interval inside this medium's box.
        const float lo = std::max(a, s.t0), hi = std::min(b, s.t1);
        if (!(hi > lo)) continue;
        const float mid = 0.5f * (lo + hi);
        if (testRegion && !where.contains(ray.at(mid))) continue;
        const Vec3 q = info.context.motion().lookupPoint(s.objectRay.at(mid));  // p unless blurred
        float* inc = &mTau[size_t(j + 1) * C];
        for (const Term& term : info.terms) {
            const size_t g = size_t(term.grid);
            const float v = term.grid < 0 ? 1.f : grids[g].sample(info.accessors[g], q);
            float x = term.scale * v;
            if (term.exponent != 1.f) x = x > 0.f ? std::pow(x, term.exponent) : 0.f;
            const float add = (hi - lo) * x;
            inc[term.channel] += add;
            if (term.channel == 0) greyTau += add;
        }
        if (greyTau > kOpaqueDepth) break;
    }
}

float RayOpticalDepth::transmittance(float t, float lambdaNm) const {
    if (mNodes == 0 || !(t > mT0)) return 1.f;
    float u = (t - mT0) / mH;
    int j = u >= float(mNodes) ? mNodes - 1 : int(u);
    float f = std::min(u - float(j), 1.f);
    const size_t C = size_t(mChannels);
    const float* a = &mTau[size_t(j) * C];
    const float* b = a + C;
    float tau = a[0] + f * (b[0] - a[0]);
    for (const SpectralComponent& s : mSpectral)
        tau += s.model->opticalDepth(lambdaNm, DepthIntegrals{a + s.first, b + s.first, f});
    return std::exp(-tau);
}

}  // namespace mirage
