#include "render/lamp_sampling.h"

#include <algorithm>
#include <cmath>
#include <new>

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

// The marched optical depth of the camera ray past which its points for the lights at
// infinity fork no path (lamp_sampling.h).
constexpr float kForkDepth = 2.f;

// An index i < n drawn with probability term[i] / total (total = their sum > 0) by u ∈ [0, 1);
// never one whose term is 0, even where u · total rounds past the last positive one.
int chooseInProportion(const float* term, int n, float total, float u) {
    int i = 0;
    for (float left = u * total; i + 1 < n && !(left < term[i]); ++i) left -= term[i];
    while (i > 0 && !(term[i] > 0.f)) --i;
    return i;
}

}  // namespace

bool samplesSky(const RenderScene& scene) {
    if (!scene.equiangular || scene.media.empty()) return false;
    for (const auto& light : scene.lights)
        if (light->infinite()) return true;
    return false;
}

bool skyPointsFork(const RenderScene& scene) {
    if (!samplesSky(scene) || scene.media.size() != 1 || scene.hasSurfaces()) return false;
    const Medium& medium = *scene.media[0];
    if (medium.emissive() || medium.fluorescent()) return false;
    for (const auto& light : scene.lights)
        if (!light->infinite()) return false;
    return true;
}

bool samplesLamps(const RenderScene& scene) {
    if (!scene.equiangular || scene.media.empty()) return false;
    for (const auto& light : scene.lights)
        if (light->origin()) return true;
    return false;
}

LampSampling::LampSampling(const RenderScene& scene, const Ray& ray, float tEnd, bool on,
                           Sampler& sampler, TrackingContext* sky, bool forks)
    : mForks(forks && sky), mRay(ray), mScene(&scene) {
    if (sky) drawSky(*sky, tEnd, sampler);
    // A fork where the ray is thin: its marched depth at most kForkDepth (lamp_sampling.h).
    for (size_t k = 0; k < mSkyCount; ++k)
        if (mSky.at[k].profile.depth > kForkDepth) mForks = false;
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
        if (!segment.empty()) new (&mLamps.at[mCount++]) Lamp{i, segment, {}};
    }
    for (size_t k = 0; k < mCount; ++k) {
        Lamp& lamp = mLamps.at[k];
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
    for (size_t k = 0; k < mCount; ++k) pass(mLamps.at[k].point);
    for (size_t k = 0; k < mSkyCount; ++k)
        for (int i = 0; i < mSky.at[k].count; ++i) pass(mSky.at[k].points[i]);
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
        if (mLamps.at[k].light == light) return &mLamps.at[k];
    return nullptr;
}

const LampSampling::SkyPoint* LampSampling::findSky(int medium) const {
    for (size_t k = 0; k < mSkyCount; ++k)
        if (mSky.at[k].medium == medium) return &mSky.at[k];
    return nullptr;
}

float LampSampling::scatterPointWeight(size_t light, const Collision& c) const {
    const Lamp* lamp = find(light);
    if (lamp) return powerWeight(scatterProxy(c.mp), lamp->segment.pdf(c.t));
    return mScene->lights[light]->infinite() ? skyWeight(c) : 1.f;
}

float LampSampling::skyWeight(const Collision& c) const {
    const SkyPoint* sky = mForks ? nullptr : findSky(c.medium);
    return sky ? powerWeight(scatterProxy(c.mp), sky->density(c.t)) : 1.f;
}

bool LampSampling::keepsScatterPoint(const Collision& c, Sampler& sampler) const {
    const SkyPoint* sky = mForks ? findSky(c.medium) : nullptr;
    if (!sky) return true;
    return sampler.get1D() < powerWeight(scatterProxy(c.mp), sky->density(c.t));
}

void LampSampling::drawSky(TrackingContext& tracking, float tEnd, Sampler& sampler) {
    for (size_t m = 0; m < tracking.size() && mSkyCount < kMaxSky; ++m) {
        const Medium& medium = tracking.medium(m);
        Medium::Context& ctx = tracking.context(m);
        const Ray r = ctx.toObject(mRay);
        float a, b;
        if (!medium.objectBounds().intersect(r.o, r.d, 0.f, tEnd, &a, &b) || !(b > a) ||
            !std::isfinite(b))
            continue;
        const SkyProfile profile = SkyProfile::march(medium, ctx, r, a, b);
        tracking.lookups += SkyProfile::kSteps;
        if (!(profile.depth > 0.f) || !std::isfinite(profile.depth)) continue;
        // One point per stratum of [0, depth), uniform in the profile's depth.
        const float u = sampler.get1D();
        SkyPoint& sky = *new (&mSky.at[mSkyCount]) SkyPoint{};
        sky.medium = int(m);
        sky.profile = profile;
        std::array<float, kSkyStrata> t, pdf;
        sky.count = profile.stratify(u, kSkyStrata, t.data(), pdf.data());
        for (int i = 0; i < sky.count; ++i) sky.points[size_t(i)] = FlightPoint{t[i], pdf[i]};
        if (sky.count) ++mSkyCount;
    }
}

void LampSampling::gatherSky(const RenderScene& scene, const SampledSpectrum& beta,
                             Sampler& sampler, ThreadState& ts, PathRecorder& rec,
                             std::optional<SkyFork>* fork) const {
    for (size_t k = 0; k < mSkyCount; ++k) {
        const SkyPoint& sky = mSky.at[k];
        const size_t m = size_t(sky.medium);
        if (rec.holdout(m)) continue;
        const Medium& medium = ts.tracking.medium(m);
        Medium::Context& ctx = ts.tracking.context(m);
        const Ray r = ctx.toObject(mRay);
        // Each point's term of the strata's sum, w(t) β T̂(0, t) σs(t) / p(t), with the
        // transmittance the flight read where it got that far: one term is lit, chosen in
        // proportion to it and divided by its probability (lamp_sampling.h).
        std::array<MediumPoint, kSkyStrata> mp;
        std::array<float, kSkyStrata> term{};
        float total = 0.f;
        for (int i = 0; i < sky.count; ++i) {
            const FlightPoint& point = sky.points[i];
            medium.eval(r.at(point.t), ctx, &mp[i]);
            ++ts.tracking.lookups;
            const SampledSpectrum known = closedFormTransmittance(ts.tracking, mRay, point.t) *
                                          (point.passed ? point.ratio : mRatio);
            term[i] = powerWeight(point.pdf, scatterProxy(mp[i])) *
                      (known * mp[i].sigmaS).average() / point.pdf;
            total += term[i];
        }
        if (!(total > 0.f)) continue;
        const int chosen = chooseInProportion(term.data(), sky.count, total, sampler.get1D());
        const FlightPoint& point = sky.points[chosen];
        const SampledSpectrum T = toPoint(point, ts.tracking, sampler);
        if (T.isZero()) continue;
        Collision c;
        c.medium = sky.medium;
        c.t = point.t;
        c.p = mRay.at(c.t);
        c.sigmaMaj = 0.f;
        c.mp = mp[chosen];
        const float w = powerWeight(point.pdf, scatterProxy(c.mp));
        const SampledSpectrum weight =
            beta * T * c.mp.sigmaS * (w * total / term[chosen]) / point.pdf;
        // Where the path goes on from the point, the second path's escape is the phase
        // function's strategy (lamp_sampling.h: Forks).
        const bool forks = mForks && fork;
        SkyDraws draws;
        rec.litInMedium(weight,
                        directLightMedium(scene, c, -mRay.d, sampler, ts, nullptr,
                                          forks ? MediumLights::SkyByEscape
                                                : MediumLights::InfiniteOnly,
                                          forks ? &draws : nullptr),
                        c.t);
        if (forks) *fork = SkyFork{c, weight, draws};
    }
}

void LampSampling::gather(const RenderScene& scene, const SampledSpectrum& beta, Sampler& sampler,
                          ThreadState& ts, PathRecorder& rec, std::optional<SkyFork>* fork) const {
    if (mSkyCount) gatherSky(scene, beta, sampler, ts, rec, fork);
    const SampledWavelengths& w = ts.tracking.wavelengths();
    const Vec3 wo = -mRay.d;
    for (size_t k = 0; k < mCount; ++k) {
        const Lamp& lamp = mLamps.at[k];
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
