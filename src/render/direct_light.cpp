#include "render/direct_light.h"

#include "light/surface_light.h"
#include "render/curved_transport.h"
#include "render/lamp_sampling.h"
#include "render/sun_shade.h"

namespace mirage {

namespace {

// The shadow ray's length short of the light: a quad light may lie on a surface (the ceiling
// of a Cornell box), which must not occlude its own light.
float shadowLength(const Vec3& target, float distance) {
    return std::isfinite(distance) ? distance - 4.f * surfaceEpsilon(target) : distance;
}

// Whether the ray from o along the unit wi meets light `i` (then *out holds the distance, the
// radiance and the pdf its sampleLi draws wi with): Light::hitLi, but for the emissive
// surfaces, which only the geometry can intersect — the first surface along wi, if it is one of
// their emitters.
bool hitLight(const RenderScene& scene, const Light& light, const Vec3& o, const Vec3& wi,
              const SampledWavelengths& w, LightSample* out) {
    const SurfaceLight* surfaces = surfaceLightOf(light);
    if (!surfaces) return light.hitLi(o, wi, w, out);
    const std::optional<SurfaceHit> hit = scene.geometry->intersect(Ray{o, wi, kInfinity});
    if (!hit || !surfaces->samples(hit->shape)) return false;
    out->wi = wi;
    out->distance = hit->t;
    out->Li = scene.geometry->materialAt(*hit).emission(w);
    out->pdf = surfaces->pdfAt(hit->material, o, hit->p, hit->ng);
    return out->pdf > 0.f;
}

// Lights at infinity along curved paths. Where a [refraction] field bends light
// (ThreadState::curved), a shadow ray towards a light at infinity follows its Fermat path, and
// the light is met where that path leaves the scene (transport/curved_connection.h), with the
// radiance L(ωe)·(n(x)/n(exit))² (the n² law):
//   - a light a direction can hit (the dome: its samples have a pdf): the path from x along a
//     direction ωi sees the light in its escape direction ωe. That is an exact estimate of
//     ∫ f L dωi whatever density drew ωi, so the light's own samples (its direction taken as
//     ωi) and the lobe's (phase function or BSDF) are both kept, weighed by the power heuristic
//     on what drew ωi: the light's pdf of ωi as a direction, and the lobe's. Unbiased; but
//     where the bending is large against a bright feature of the light (a sun drawn in an
//     image dome) neither strategy finds it often: noise, not bias;
//   - a delta light at infinity (the sun): the one path that leaves along its direction, found
//     by Newton's method, its irradiance divided by the solid-angle ratio |dωe/dωi| there. What
//     is lost: a path the method does not find (a second image of the sun through a strong
//     layer; a start whose first guess, the straight direction, is blocked by a surface).
//     Aiming the dome's samples the same way would lose those paths from every dome sample:
//     measured 2.7 % darker than the photon pass on the linear-profile fog of
//     tests/physics/curved_shadow_test.cpp, against 0.3 % for the escape form.
// Lights at a finite distance (point, spot, quad) keep straight shadow rays: their connection
// is a two-point boundary problem per sample (and the lamps' distance sampling,
// render/lamp_sampling.h, is weighed against straight shadow rays), left for later: the
// straight-ray approximation, exact as the bending vanishes.

// The scattering at a vertex as a shadow connection weighs it: f(ωi) (the phase function, or
// f |cos θi| at a surface), its density of ωi, a sample of it (weight f/pdf), and where a
// shadow path along ωi starts (off a surface).
class ShadowLobe {
public:
    virtual SampledSpectrum eval(const Vec3& wi) const = 0;
    virtual float pdf(const Vec3& wi) const = 0;
    virtual bool sample(Sampler& sampler, Vec3* wi, SampledSpectrum* weight, float* pdf) const = 0;
    virtual Vec3 origin(const Vec3& wi) const = 0;

protected:
    ~ShadowLobe() = default;
};

// Whether `light`, sampled at a point (ls, when sampleLi drew one), is reached along curved paths.
bool curvedConnection(const ThreadState& ts, const Light& light, const LightSample* ls) {
    return ts.curved && (light.infinite() || (ls && std::isinf(ls->distance)));
}

// The escape connection along ωi: L(ωe) T (n(x)/n(exit))², 0 when blocked.
SampledSpectrum escapedAlong(const Light& light, const ShadowLobe& lobe, const Vec3& wi,
                             Sampler& sampler, ThreadState& ts) {
    const CurvedTransport& curved = *ts.curved;
    const SampledWavelengths& w = ts.tracking.wavelengths();
    const auto e = escapeCurved(curved.shadow(), Ray{lobe.origin(wi), wi}, w.lambda[0],
                                &ts.tracking, &sampler);
    LightSample hs;
    if (!e || !light.hitLi(lobe.origin(wi), e->direction, w, &hs)) return SampledSpectrum(0.f);
    return hs.Li * e->T * e->radianceScale();
}

// One light at infinity's term along curved paths (the estimators above). ls: the light's
// sample, null when it drew none; deltaWeight: a delta light's weight against other strategies.
SampledSpectrum curvedLightTerm(const Light& light, const LightSample* ls, const ShadowLobe& lobe,
                                float deltaWeight, Sampler& sampler, ThreadState& ts) {
    const SampledWavelengths& w = ts.tracking.wavelengths();
    if (ls && !(ls->pdf > 0.f)) {
        const CurvedTransport& curved = *ts.curved;
        const auto aim = aimCurved(curved.shadow(), lobe.origin(ls->wi), ls->wi, w.lambda[0],
                                   ts.tracking, sampler);
        if (!aim || !(aim->spread > 0.f)) return SampledSpectrum(0.f);
        return lobe.eval(aim->wi) * ls->Li * aim->escape.T *
               (aim->escape.radianceScale() * deltaWeight / aim->spread);
    }
    SampledSpectrum term(0.f);
    if (ls) {
        const SampledSpectrum f = lobe.eval(ls->wi);
        if (!f.isZero())
            term += f * escapedAlong(light, lobe, ls->wi, sampler, ts) *
                    (powerHeuristic(ls->pdf, lobe.pdf(ls->wi)) / ls->pdf);
    }
    Vec3 wi;
    SampledSpectrum weight;
    float pdf;
    if (lobe.sample(sampler, &wi, &weight, &pdf)) {
        LightSample straight;  // the light's density of ωi, as its own sample would draw it
        straight.pdf = 0.f;
        light.hitLi(lobe.origin(wi), wi, w, &straight);
        term +=
            weight * escapedAlong(light, lobe, wi, sampler, ts) * powerHeuristic(pdf, straight.pdf);
    }
    return term;
}

// The phase function at a medium point as a shadow connection's lobe.
class PhaseLobe final : public ShadowLobe {
public:
    PhaseLobe(const Medium& m, const Collision& c, const Vec3& wo) : mM(m), mC(c), mWo(wo) {}
    SampledSpectrum eval(const Vec3& wi) const override { return mM.phaseEval(mC.mp, -wi, mWo); }
    float pdf(const Vec3& wi) const override { return mM.phasePdf(mC.mp, -mWo, wi); }
    bool sample(Sampler& sampler, Vec3* wi, SampledSpectrum* weight, float* pdf) const override {
        const float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
        *wi = mM.phaseSample(mC.mp, -mWo, uc, u1, u2, weight, pdf);
        return *pdf > 0.f;
    }
    Vec3 origin(const Vec3&) const override { return mC.p; }

private:
    const Medium& mM;
    const Collision& mC;
    Vec3 mWo;
};

// A diffuse surface's BSDF, f |cos θi|, as a shadow connection's lobe: 0 for light from behind
// the geometric surface (Lambertian surfaces are two-sided but opaque).
class SurfaceLobe final : public ShadowLobe {
public:
    SurfaceLobe(const SurfaceHit& hit, const Material& material, const Vec3& wo,
                const SampledWavelengths& w)
        : mHit(hit),
          mMaterial(material),
          mFrame(hit.ns),
          mWoL(mFrame.toLocal(wo)),
          mSide(dot(wo, hit.ng)),
          mW(w) {}
    SampledSpectrum eval(const Vec3& wi) const override {
        if (dot(wi, mHit.ng) * mSide <= 0.f) return SampledSpectrum(0.f);
        const Vec3 wiL = mFrame.toLocal(wi);
        return mMaterial.eval(mWoL, wiL, mW) * std::abs(wiL.z);
    }
    float pdf(const Vec3& wi) const override { return mMaterial.pdf(mWoL, mFrame.toLocal(wi)); }
    bool sample(Sampler& sampler, Vec3* wi, SampledSpectrum* weight, float* pdf) const override {
        const float uc = sampler.get1D(), v1 = sampler.get1D(), v2 = sampler.get1D();
        BsdfSample bs;
        if (!mMaterial.sample(mWoL, uc, v1, v2, mW, TransportMode::Radiance, &bs) || bs.specular)
            return false;
        *wi = mFrame.toWorld(bs.wi);
        *pdf = mMaterial.pdf(mWoL, bs.wi);
        if (!(*pdf > 0.f)) return false;
        *weight = eval(*wi) / *pdf;
        return true;
    }
    Vec3 origin(const Vec3& wi) const override { return spawnRay(mHit, wi).o; }

private:
    const SurfaceHit& mHit;
    const Material& mMaterial;
    Frame mFrame;
    Vec3 mWoL;
    float mSide;
    const SampledWavelengths& mW;
};

}  // namespace

// Light arriving at a medium point, by next-event estimation. A light a direction can hit (the
// quad, the dome, the emissive surfaces) is sampled twice, by the light and by the phase function,
// the two combined by multiple importance sampling (Veach 1997): in a strongly forward medium
// (marine particles, HG g = 0.92, p up to 26/sr against a mean of 1/4π) the light's own samples
// alone score rare directions along the lobe ~300 times the mean, the speckles of a lit water box;
// phase samples take those directions at the lobe's own density. Both are shadow rays with the same
// transmittance estimate, so the sum stays an unbiased estimate of ∫ T p L dω.
//
// The lights at infinity under MediumLights::SkyByEscape: the phase function's strategy is the
// path's own continuation, which the path tracer flies anyway (pbrt-v4's volumetric path tracer
// is built so, Pharr et al. 2023 §14.2.3). It scores the light where it leaves the scene with
// the same power weight (skyAtEscape): delta tracking gets out with probability T, so its mean
// is the shadow ray's, for no ray of its own. A uniform dome draws no sample of its own at all:
// p L / (pdf of a uniform direction) is up to 4π p_max times the mean in a forward medium, where
// the phase function's sample scores T L ≤ L. Measured on the sky-white regime (an albedo-0.99,
// g 0.85 cloud under a white dome, docs/regimes.md; 16 samples, seeds 1 and 2): two shadow rays
// per vertex, relative variance 0.149 for 4.06 CPU s; the continuation alone (this), 0.087 for
// 1.85 s: 3.8× at equal time. Inside such a cloud most shadow rays are ratio-tracked through
// tens of optical depths for a transmittance of ~0, while the continuation, the path itself,
// carries the light of the many scatterings beyond.
//
// Deep in such a cloud under a map with a sun, the lights' own samples still cost a shadow ray
// at every vertex, and most find T ~ 0. So a vertex that leaves the lights at infinity to its
// escape draws their samples with a probability (SkyDraws): 1, but kDarkSkyRate after a drawn
// sample of the path found no light, until one finds some again. A drawn sample then counts
// 1/rate of itself and its density in the power heuristic is rate · pdf, on both sides
// (skyAtEscape), so the two strategies still sum to one estimate of the light (Veach 1997,
// §9.2.4: a strategy's sample count enters the heuristic). Where it skips, the escape takes the
// light alone; it draws a sun's narrow cone rarely, so a vertex just coming out of the dark pays
// with 1/rate: the rate is a function of the path so far, so the estimate stays unbiased.
// Measured on the sky-hdr regime (64 samples, two seeds, relMSE against the reference × CPU
// seconds): kDarkSkyRate 1 (every vertex), 1.07; 0.7, 0.96; 0.5, 0.89; 0.35, 0.96 (seed noise,
// 32 samples: 0.1 lost, 2.2). Where the scene's sky has a sun, the rate is instead a function of
// the vertex's position, from the sun's optical depth there (render/sun_shade.h): 1.27× lower
// again on sky-hdr.
constexpr float kDarkSkyRate = 0.5f;

SampledSpectrum directLightMedium(const RenderScene& scene, const Collision& c, const Vec3& wo,
                                  Sampler& sampler, ThreadState& ts, const LampSampling* lamps,
                                  MediumLights which, SkyDraws* sky) {
    SampledSpectrum L(0.f);
    // Whether this vertex draws the lights at infinity's own samples (SkyDraws): one draw for
    // all of them, made only where the rate is below 1.
    float skyRate = 1.f;
    bool drawsSky = true, skyDrawn = false, skyFound = false;
    if (sky && which == MediumLights::SkyByEscape) {
        skyRate = sky->shade ? sky->shade->drawRate(c.p) : sky->dark ? kDarkSkyRate : 1.f;
        drawsSky = skyRate >= 1.f || sampler.get1D() < skyRate;
    }
    const Medium& m = ts.tracking.medium(c.medium);
    const SampledWavelengths& w = ts.tracking.wavelengths();
    SampledSpectrum* split = ts.startLightSplit();
    // One shadow ray's transmittance times the radiance it carries; 0 when blocked.
    auto shadowed = [&](const LightSample& ls) {
        if (scene.hasSurfaces() &&
            scene.geometry->occluded(c.p, ls.wi,
                                     shadowLength(c.p + ls.wi * ls.distance, ls.distance)))
            return SampledSpectrum(0.f);
        Ray shadow{c.p, ls.wi, ls.distance};
        return transmittance(ts.tracking, shadow, ls.distance, sampler) * ls.Li;
    };
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        if (which == MediumLights::InfiniteOnly && !light->infinite()) continue;
        const float share = lamps ? lamps->scatterPointWeight(i, c) : 1.f;
        if (!(share > 0.f)) continue;
        // A uniform dome is drawn by the phase function alone (above).
        const bool phaseOnly = light->uniformRadiance() && !ts.curved;
        const bool escapes = which == MediumLights::SkyByEscape && light->infinite();
        if (escapes && (phaseOnly || !drawsSky)) continue;
        float u1, u2;
        sampler.get2D(&u1, &u2);  // one pair of dimensions: stratified over the light
        SampledSpectrum term(0.f);
        LightSample ls;
        const bool sampled = !phaseOnly && light->sampleLi(c.p, u1, u2, w, &ls);
        if (sampled && escapes && skyRate < 1.f) {
            ls.Li /= skyRate;
            ls.pdf *= skyRate;
        }
        const bool curved = curvedConnection(ts, *light, sampled ? &ls : nullptr);
        if (curved) {
            term = curvedLightTerm(*light, sampled ? &ls : nullptr, PhaseLobe(m, c, wo), share,
                                   sampler, ts);
        } else if (sampled) {
            // The light travels along −wi into the point and leaves along wo.
            const SampledSpectrum phase = m.phaseEval(c.mp, -ls.wi, wo);
            const float mis =
                ls.pdf > 0.f ? powerHeuristic(ls.pdf, m.phasePdf(c.mp, -wo, ls.wi)) : share;
            if (!phase.isZero() && mis > 0.f) term += shadowed(ls) * phase * mis;
        }
        if (!curved && !escapes && (phaseOnly || ls.pdf > 0.f)) {
            // The phase function's sample, for a light a direction can hit (its samples have a pdf)
            // that the point sees the emitting side of.
            SampledSpectrum weight;
            float pdf;
            const float uc = sampler.get1D(), v1 = sampler.get1D(), v2 = sampler.get1D();
            const Vec3 wi = m.phaseSample(c.mp, -wo, uc, v1, v2, &weight, &pdf);
            LightSample hs;
            if (pdf > 0.f && hitLight(scene, *light, c.p, wi, w, &hs))
                term += shadowed(hs) * weight * (phaseOnly ? 1.f : powerHeuristic(pdf, hs.pdf));
        }
        // The share weighs every strategy but a delta light's sample, which took it as its
        // weight (curved paths' too: curvedLightTerm's deltaWeight).
        if (!(sampled && !(ls.pdf > 0.f))) term *= share;
        if (escapes) {
            skyDrawn = true;
            skyFound = skyFound || !term.isZero();
        }
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    if (sky) {
        sky->rate = skyRate;
        if (skyDrawn) sky->dark = !skyFound;
    }
    return L;
}

SampledSpectrum skyAtEscape(const RenderScene& scene, const Ray& ray, float phasePdf,
                            float skyRate, const SampledWavelengths& w, ThreadState& ts) {
    SampledSpectrum L(0.f);
    SampledSpectrum* split = ts.startLightSplit();
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = *scene.lights[i];
        LightSample hs;
        if (!light.infinite() || !light.hitLi(ray.o, ray.d, w, &hs)) continue;
        const float mis =
            light.uniformRadiance() ? 1.f : powerHeuristic(phasePdf, skyRate * hs.pdf);
        const SampledSpectrum term = hs.Li * mis;
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    return L;
}

// Light arriving at a diffuse surface point, by next-event estimation. A light at infinity (the
// dome) is sampled twice, by the light and by the BSDF, combined by multiple importance sampling
// as in a medium: a constant dome drawn uniformly over the sphere sends half its samples below
// the surface, and the BSDF's cosine lobe draws exactly the directions that count. So are the
// emissive surfaces, which may be large and near (a glowing wall beside the point), where
// points drawn on them by area score d²/cos without bound. A quad's small solid angle would
// waste most BSDF samples, so it keeps its own sampling alone.
SampledSpectrum directLightSurface(const RenderScene& scene, const SurfaceHit& hit,
                                   const Material& material, const Vec3& wo, Sampler& sampler,
                                   ThreadState& ts) {
    SampledSpectrum L(0.f);
    const SampledWavelengths& w = ts.tracking.wavelengths();
    Frame frame(hit.ns);
    Vec3 woL = frame.toLocal(wo);
    const float side = dot(wo, hit.ng);
    SampledSpectrum* split = ts.startLightSplit();
    // T f |cos θi| for a direction towards the light (Li left to the caller); 0 when the light
    // is behind the surface, or blocked.
    auto shadowed = [&](const LightSample& ls) {
        // Light from behind the geometric surface cannot reach the viewer's side.
        if (dot(ls.wi, hit.ng) * side <= 0.f) return SampledSpectrum(0.f);
        const Vec3 wiL = frame.toLocal(ls.wi);
        const SampledSpectrum f = material.eval(woL, wiL, w);
        if (f.isZero()) return SampledSpectrum(0.f);
        Ray shadow = spawnRay(hit, ls.wi, ls.distance);
        float len = shadowLength(hit.p + ls.wi * ls.distance, ls.distance);
        if (scene.geometry->occluded(shadow.o, ls.wi, len)) return SampledSpectrum(0.f);
        return transmittance(ts.tracking, shadow, ls.distance, sampler) * f * std::abs(wiL.z);
    };
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light* light = scene.lights[i].get();
        const bool twoStrategies = light->infinite() || surfaceLightOf(*light);
        float u1, u2;
        sampler.get2D(&u1, &u2);  // one pair of dimensions: stratified over the light
        SampledSpectrum term(0.f);
        LightSample ls;
        const bool sampled = light->sampleLi(hit.p, u1, u2, w, &ls);
        const bool curved = curvedConnection(ts, *light, sampled ? &ls : nullptr);
        if (curved) {
            term = curvedLightTerm(*light, sampled ? &ls : nullptr,
                                   SurfaceLobe(hit, material, wo, w), 1.f, sampler, ts);
        } else if (sampled) {
            const float mis = twoStrategies && ls.pdf > 0.f
                                  ? powerHeuristic(ls.pdf, material.pdf(woL, frame.toLocal(ls.wi)))
                                  : 1.f;
            term += shadowed(ls) * ls.Li * mis;
        }
        if (!curved && twoStrategies) {
            const float uc = sampler.get1D(), v1 = sampler.get1D(), v2 = sampler.get1D();
            BsdfSample bs;
            LightSample hs;
            if (material.sample(woL, uc, v1, v2, w, TransportMode::Radiance, &bs) && !bs.specular) {
                const float pdf = material.pdf(woL, bs.wi);
                const Vec3 wi = frame.toWorld(bs.wi);
                if (pdf > 0.f && hitLight(scene, *light, spawnRay(hit, wi).o, wi, w, &hs))
                    term += shadowed(hs) * hs.Li * (powerHeuristic(pdf, hs.pdf) / pdf);
            }
        }
        L += term;
        if (split) split[scene.lightGroupSlot(i)] += term;
    }
    return L;
}

SampledSpectrum escapedRadiance(const RenderScene& scene, const Vec3& d,
                                const SampledWavelengths& w, bool cameraRay) {
    SampledSpectrum L(0.f);
    for (const auto& light : scene.lights)
        if (light->infinite()) L += light->escapedRadiance(d, w, cameraRay);
    return L;
}

}  // namespace mirage
