#include "render/lobe_walk.h"

#include <optional>

#include "render/direct_light.h"
#include "transport/path_vertex.h"

namespace mirage {

namespace {

// A lobe walk from its first ray on, its first direction's weight in its throughput and its
// run's sum in its lobeRatios; rec is its branch of the path's record.
void lobeWalk(const RenderScene& scene, CameraPath walk, int maxDepth, Sampler& sampler,
              ThreadState& ts, PathRecorder rec) {
    PathThroughput& throughput = walk.throughput;
    for (++walk.depth; throughput.alive() && walk.depth < maxDepth; ++walk.depth) {
        const SurfaceAhead ahead = surfaceAhead(scene, walk.ray);
        std::optional<Collision> y;
        const bool through =
            trackCollisions(ts.tracking, walk.ray, ahead.tEnd, sampler, [&](const Collision& c) {
                const MediumEvent e = chooseEvent(c, throughput, sampler).event;
                if (e == MediumEvent::Null) return Track::Continue;
                if (e == MediumEvent::Scattered) y = c;
                return Track::Stop;
            });
        if (!y) {
            if (through && !ahead.hit) escapeToDome(scene, walk, ts, rec);
            return;
        }
        // As on the path (scatterInMedium), the lights at infinity are left to the walk's
        // continuation, which goes on with probability q: its escape counts 1/q of itself.
        const bool escapes = !ts.curved && walk.depth + 1 < maxDepth;
        const float share = 1.f / (1.f + walk.lobeRatios);
        SkyDraws sky{walk.skyDark, walk.sunShade};
        rec.litInMedium(throughput.beta * share,
                        directLightMedium(scene, *y, -walk.ray.d, sampler, ts, nullptr,
                                          escapes ? MediumLights::SkyByEscape
                                                  : MediumLights::All,
                                          &sky),
                        y->t);
        rec.scatteredInMedium(y->t);
        walk.skyDark = sky.dark;
        walk.escapePdf = 0.f;
        if (sampler.get1D() >= kLobeWalkGoesOn) return;
        float pdf;
        const Vec3 dir = samplePhase(ts.tracking.medium(y->medium), *y, walk.ray.d, sampler,
                                     &throughput, &pdf);
        if (escapes) walk.leaveSkyToEscape(pdf, share / kLobeWalkGoesOn, sky.rate);
        walk.lobeRatios =
            kLobeWalkGoesOn * walk.lobeRatios +
            walk.walkStart * LightLobes(scene, y->p, walk.wavelengths).pdf(dir) / pdf;
        walk.ray = Ray{y->p, dir, kInfinity};
    }
}

}  // namespace

void walkFromMedium(const RenderScene& scene, const LightLobes& lobes, const Collision& x,
                    const CameraPath& path, int maxDepth, Sampler& sampler, ThreadState& ts,
                    const PathRecorder& rec) {
    const float ul = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
    const Vec3 dir = lobes.sample(ul, u1, u2);
    const Medium& m = ts.tracking.medium(x.medium);
    const Vec3 dirIn = path.ray.d;
    const float pdf = m.phasePdf(x.mp, dirIn, dir);
    if (!(pdf > 0.f)) return;
    CameraPath walk = path;
    walk.throughput.beta *= m.phaseEval(x.mp, dirIn, dir) / pdf;
    walk.ray = Ray{x.p, dir, kInfinity};
    walk.lobeRatios = kLobeWalkGoesOn * path.lobeRatios + path.walkStart * lobes.pdf(dir) / pdf;
    lobeWalk(scene, walk, maxDepth, sampler, ts, rec.branch());
}

void walkFromSurface(const RenderScene& scene, const LightLobes& lobes, const SurfaceHit& hit,
                     const CameraPath& path, int maxDepth, Sampler& sampler, ThreadState& ts,
                     const PathRecorder& rec) {
    const float ul = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
    const Vec3 dir = lobes.sample(ul, u1, u2);
    const Vec3 dirIn = path.ray.d;
    // A Lambertian surface reflects only: a lobe's direction through it scores f = 0.
    if ((dot(dir, hit.ng) > 0.f) != (dot(-dirIn, hit.ng) > 0.f)) return;
    const Material& mat = scene.geometry->materialAt(hit);
    const Frame frame(hit.ns);
    const Vec3 woL = frame.toLocal(-dirIn), wiL = frame.toLocal(dir);
    const float pdf = mat.pdf(woL, wiL);
    if (!(pdf > 0.f)) return;
    CameraPath walk = path;
    walk.throughput.beta *= mat.eval(woL, wiL, path.wavelengths) * (std::abs(wiL.z) / pdf);
    walk.ray = spawnRay(hit, dir);
    walk.lobeRatios = lobes.pdf(dir) / pdf;
    lobeWalk(scene, walk, maxDepth, sampler, ts, rec.branch());
}

}  // namespace mirage
