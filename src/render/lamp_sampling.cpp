#include "render/lamp_sampling.h"

#include <algorithm>
#include <cmath>

#include "light/lamp.h"
#include "render/direct_light.h"

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

bool samplesSky(const RenderScene& scene) {
    if (!scene.equiangular || scene.media.empty()) return false;
    for (const auto& light : scene.lights)
        if (light->infinite()) return true;
    return false;
}

bool samplesLamps(const RenderScene& scene) {
    if (!scene.equiangular || scene.media.empty()) return false;
    for (const auto& light : scene.lights)
        if (light->origin()) return true;
    return false;
}

LampSampling::LampSampling(const RenderScene& scene, const Ray& ray, float tEnd, bool on,
                           Sampler& sampler, TrackingContext* sky)
    : mRay(ray), mScene(&scene) {
    if (sky) drawSky(*sky, tEnd, sampler);
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
        if (!segment.empty()) mLamps[mCount++] = Lamp{i, segment, {}};
    }
    for (size_t k = 0; k < mCount; ++k) {
        Lamp& lamp = mLamps[k];
        lamp.point.t = lamp.segment.sample(sampler.get1D());
        lamp.point.pdf = lamp.segment.pdf(lamp.point.t);
    }
}

void LampSampling::passPoints(float t) {
    auto pass = [&](FlightPoint& p) {
        if (p.passed || !(t > p.t)) return;
        p.ratio = mRatio;
        p.passed = true;
    };
    for (size_t k = 0; k < mCount; ++k) pass(mLamps[k].point);
    for (size_t k = 0; k < mSkyCount; ++k) pass(mSky[k].point);
}

void LampSampling::ratioTrack(const Collision& c, const TrackingContext& tracking) {
    passPoints(c.t);
    mLastT = c.t;
    if (tracking.medium(size_t(c.medium)).closedFormTransmittance()) return;
    mRatio *= SampledSpectrum(1.f) - (c.mp.sigmaA + c.mp.sigmaS) / c.sigmaMaj;
}

void LampSampling::flightEnded(bool reached) {
    if (!reached) return;
    // No tentative collision lies between the last one and any point left: the product is
    // complete.
    passPoints(kInfinity);
}

SampledSpectrum LampSampling::toPoint(const FlightPoint& lamp, TrackingContext& tracking,
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
    if (lamp) return powerWeight(scatterProxy(c.mp), lamp->segment.pdf(c.t));
    for (size_t k = 0; k < mSkyCount; ++k)
        if (mSky[k].medium == c.medium && c.t < mSky[k].tCap && mScene->lights[light]->infinite())
            return 0.f;
    return 1.f;
}

// The majorant's optical depth along the camera ray that its points for the lights at
// infinity cover (lamp_sampling.h): beyond it, delta tracking's scattering points alone.
constexpr float kSkyDepthCap = 3.f;

void LampSampling::drawSky(TrackingContext& tracking, float tEnd, Sampler& sampler) {
    for (size_t m = 0; m < tracking.size() && mSkyCount < kMaxSky; ++m) {
        const Medium& medium = tracking.medium(m);
        const Ray r = tracking.context(m).toObject(mRay);
        const float path = tracking.pathMajorant(m);
        // The first walk: the majorant's optical depth over the segment, up to the cap.
        float depth = 0.f, tCap = tEnd;
        MajorantGrid::Walk walk(medium.majorant(), r.o, r.d, 0.f, tEnd);
        for (MajorantGrid::Walk::Segment s; walk.next(&s); walk.advanceTo(s.t1)) {
            const float sigma = path >= 0.f ? path : s.sigmaMaj;
            if (!(sigma > 0.f)) continue;
            const float cell = sigma * (s.t1 - s.t0);
            if (depth + cell >= kSkyDepthCap) {
                tCap = s.t0 + (kSkyDepthCap - depth) / sigma;
                depth = kSkyDepthCap;
                break;
            }
            depth += cell;
        }
        const float u = sampler.get1D();
        if (!(depth > 0.f)) continue;
        // The point: the exponential of the majorant truncated at `depth`, by inversion.
        const float mass = -std::expm1(-depth);
        const float tau = std::min(-std::log1p(-u * mass), depth);
        MajorantGrid::Walk second(medium.majorant(), r.o, r.d, 0.f, tEnd);
        float t, sigma;
        if (!nextTentativeCollision(second, 0.f, tau, &t, &sigma, path)) continue;
        SkyPoint& p = mSky[mSkyCount++];
        p.medium = int(m);
        p.tCap = tCap;
        p.point.t = t;
        p.point.pdf = sigma * std::exp(-tau) / mass;
    }
}

void LampSampling::gatherSky(const RenderScene& scene, const SampledSpectrum& beta,
                             Sampler& sampler, ThreadState& ts, PathRecorder& rec) const {
    for (size_t k = 0; k < mSkyCount; ++k) {
        const SkyPoint& sky = mSky[k];
        const size_t m = size_t(sky.medium);
        if (rec.holdout(m) || !(sky.point.pdf > 0.f)) continue;
        const Medium& medium = ts.tracking.medium(m);
        Medium::Context& ctx = ts.tracking.context(m);
        Collision c;
        c.medium = sky.medium;
        c.t = sky.point.t;
        c.p = mRay.at(c.t);
        c.sigmaMaj = 0.f;
        medium.eval(ctx.toObject(mRay).at(c.t), ctx, &c.mp);
        ++ts.tracking.lookups;
        if (c.mp.sigmaS.isZero()) continue;
        const SampledSpectrum T = toPoint(sky.point, ts.tracking, sampler);
        if (T.isZero()) continue;
        const SampledSpectrum weight = beta * T * c.mp.sigmaS / sky.point.pdf;
        rec.litInMedium(
            weight,
            directLightMedium(scene, c, -mRay.d, sampler, ts, nullptr, MediumLights::InfiniteOnly),
            c.t);
    }
}

void LampSampling::gather(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                          ThreadState& ts, PathRecorder& rec) const {
    if (mSkyCount) gatherSky(scene, beta, sampler, ts, rec);
    const SampledWavelengths& w = ts.tracking.wavelengths();
    const Vec3 wo = -mRay.d;
    for (size_t k = 0; k < mCount; ++k) {
        const Lamp& lamp = mLamps[k];
        const float t = lamp.point.t, pe = lamp.point.pdf;
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
            toPoint(lamp.point, ts.tracking, sampler) * scattered * toLamp * ls.Li / pe;
        if (SampledSpectrum* split = ts.startLightSplit())
            split[scene.lightGroupSlot(lamp.light)] += term;
        rec.litInMedium(beta, term, t);
    }
}

}  // namespace mirage
