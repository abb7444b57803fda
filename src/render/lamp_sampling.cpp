#include "render/lamp_sampling.h"

#include <algorithm>

#include "light/lamp.h"

namespace mirage {

namespace {

// Power heuristic (Veach 1997, §9.2.1, β = 2) of density a against b.
float powerWeight(float a, float b) {
    const float a2 = a * a, sum = a2 + b * b;
    return sum > 0.f ? a2 / sum : 0.f;
}

// The part of the ray over (0, tEnd) inside the hull of the media's bounds: where a point can
// scatter. False when the ray misses them.
bool mediaSpan(const RenderScene& scene, const Ray& ray, float tEnd, float* a, float* b) {
    bool any = false;
    for (const auto& m : scene.media) {
        float t0, t1;
        if (!m->worldBounds().intersect(ray.o, ray.d, 0.f, tEnd, &t0, &t1)) continue;
        *a = any ? std::min(*a, t0) : t0;
        *b = any ? std::max(*b, t1) : t1;
        any = true;
    }
    return any && *b > *a && std::isfinite(*b);
}

// The scattering coefficient's mean over the path's wavelengths: the proxy of delta
// tracking's density of scattering points (lamp_sampling.h).
float scatterProxy(const MediumPoint& mp) { return mp.sigmaS.average(); }

}  // namespace

bool samplesLamps(const RenderScene& scene) {
    if (!scene.equiangular || scene.media.empty()) return false;
    for (const auto& light : scene.lights)
        if (light->origin()) return true;
    return false;
}

LampSampling::LampSampling(const RenderScene& scene, const Ray& ray, float tEnd, bool on,
                           Sampler& sampler)
    : mRay(ray) {
    float a = 0.f, b = 0.f;
    if (!on || !mediaSpan(scene, ray, tEnd, &a, &b)) return;
    for (size_t i = 0; i < scene.lights.size() && mCount < kMaxLamps; ++i) {
        const std::optional<LightOrigin> lamp = scene.lights[i]->origin();
        const auto* shape = dynamic_cast<const mirage::Lamp*>(scene.lights[i].get());
        const Vec3 apex = shape ? shape->coneApex() : lamp ? lamp->p : Vec3(0.f);
        float t0 = a, t1 = b;
        if (!lamp || !coneInterval(ray.o, ray.d, Cone{apex, lamp->axis, lamp->cosCone}, &t0, &t1))
            continue;
        const EquiangularSegment segment(ray.o, ray.d, t0, t1, lamp->p);
        if (!segment.empty()) mLamps[mCount++] = Lamp{i, segment};
    }
    for (size_t k = 0; k < mCount; ++k) {
        Lamp& lamp = mLamps[k];
        lamp.t = lamp.segment.sample(sampler.get1D());
        lamp.pdf = lamp.segment.pdf(lamp.t);
    }
}

void LampSampling::ratioTrack(const Collision& c, const TrackingContext& tracking) {
    for (size_t k = 0; k < mCount; ++k) {
        Lamp& lamp = mLamps[k];
        if (lamp.passed || !(c.t > lamp.t)) continue;
        lamp.ratio = mRatio;
        lamp.passed = true;
    }
    mLastT = c.t;
    if (tracking.medium(size_t(c.medium)).closedFormTransmittance()) return;
    mRatio *= SampledSpectrum(1.f) - (c.mp.sigmaA + c.mp.sigmaS) / c.sigmaMaj;
}

void LampSampling::flightEnded(bool reached) {
    if (!reached) return;
    // No tentative collision lies between the last one and any point left: the product is
    // complete.
    for (size_t k = 0; k < mCount; ++k) {
        if (mLamps[k].passed) continue;
        mLamps[k].ratio = mRatio;
        mLamps[k].passed = true;
    }
}

SampledSpectrum LampSampling::toPoint(const Lamp& lamp, TrackingContext& tracking,
                                      Sampler& sampler) const {
    const SampledSpectrum T =
        closedFormTransmittance(tracking, mRay, lamp.t) * (lamp.passed ? lamp.ratio : mRatio);
    if (lamp.passed || !(T.maxValue() > 0.f)) return T;
    // The flight stopped at mLastT, short of the point: the rest is tracked afresh.
    const float rest = lamp.t - mLastT;
    return T * trackedTransmittance(tracking, Ray{mRay.at(mLastT), mRay.d, rest}, rest, sampler);
}

const LampSampling::Lamp* LampSampling::find(size_t light) const {
    for (size_t k = 0; k < mCount; ++k)
        if (mLamps[k].light == light) return &mLamps[k];
    return nullptr;
}

float LampSampling::scatterPointWeight(size_t light, const Collision& c) const {
    const Lamp* lamp = find(light);
    return lamp ? powerWeight(scatterProxy(c.mp), lamp->segment.pdf(c.t)) : 1.f;
}

void LampSampling::gather(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                          ThreadState& ts, PathRecorder& rec) const {
    const SampledWavelengths& w = ts.tracking.wavelengths();
    const Vec3 wo = -mRay.d;
    for (size_t k = 0; k < mCount; ++k) {
        const Lamp& lamp = mLamps[k];
        const float t = lamp.t, pe = lamp.pdf;
        const Vec3 x = mRay.at(t);
        // A point lamp's light at x is one direction; a sphere's is an integral over the cone
        // it subtends, drawn at random like next-event estimation's so that the estimate stays
        // unbiased (the weights depend on t alone).
        float u1 = 0.5f, u2 = 0.5f;
        const auto* shape = dynamic_cast<const mirage::Lamp*>(scene.lights[lamp.light].get());
        if (shape && shape->radius() > 0.f) sampler.get2D(&u1, &u2);
        LightSample ls;
        if (!(pe > 0.f) || !scene.lights[lamp.light]->sampleLi(x, u1, u2, w, &ls)) continue;
        // What scatters towards wo at x, each medium by its phase function and its weight.
        SampledSpectrum scattered(0.f);
        for (size_t m = 0; m < ts.tracking.size(); ++m) {
            const Medium& medium = ts.tracking.medium(m);
            if (rec.holdout(m)) continue;  // a holdout the camera sees scatters nothing
            Medium::Context& ctx = ts.tracking.context(m);
            const Vec3 p = ctx.toObject(mRay).at(t);
            if (!medium.objectBounds().contains(p)) continue;
            MediumPoint mp;
            medium.eval(p, ctx, &mp);
            ++ts.tracking.lookups;
            if (mp.sigmaS.isZero()) continue;
            scattered +=
                mp.sigmaS * medium.phaseEval(mp, -ls.wi, wo) * powerWeight(pe, scatterProxy(mp));
        }
        if (scattered.isZero()) continue;
        if (scene.hasSurfaces() && scene.geometry->occluded(x, ls.wi, ls.distance)) continue;
        const SampledSpectrum toLamp =
            transmittance(ts.tracking, Ray{x, ls.wi, ls.distance}, ls.distance, sampler);
        if (toLamp.isZero()) continue;
        const SampledSpectrum term =
            toPoint(lamp, ts.tracking, sampler) * scattered * toLamp * ls.Li / pe;
        if (SampledSpectrum* split = ts.startLightSplit())
            split[scene.lightGroupSlot(lamp.light)] += term;
        rec.litInMedium(beta, term, t);
    }
}

}  // namespace mirage
