// The steps camera estimators share (camera_path.h says which and why).
#include "render/camera_path.h"

#include <cmath>

#include "light/surface_light.h"
#include "render/camera_ray_data.h"
#include "render/direct_light.h"
#include "transport/scatter_point.h"

namespace mirage {

namespace {

// Whether next-event estimation samples the emission of the scene's shape `shape`.
bool sampledEmitter(const RenderScene& scene, int shape) {
    for (const auto& light : scene.lights)
        if (const SurfaceLight* s = surfaceLightOf(*light)) return s->samples(shape);
    return false;
}

}  // namespace

SurfaceAhead surfaceAhead(const RenderScene& scene, const Ray& ray) {
    SurfaceAhead ahead;
    if (scene.hasSurfaces()) ahead.hit = scene.geometry->intersect(ray);
    ahead.tEnd = ahead.hit ? ahead.hit->t : ray.tMax;
    return ahead;
}

bool scatterAlongFlight(const RenderScene& scene, const SurfaceAhead& ahead,
                        const ScatterGuide* guide, bool nee, Sampler& sampler, ThreadState& ts,
                        CameraPath& path, PathRecorder& rec) {
    PathThroughput& throughput = path.throughput;
    const ScatterPointWalk walk = chooseScatterPoints(
        ts.tracking, path.ray, ahead.tEnd, sampler, rec.flightEmission(throughput.beta),
        rec.cameraRayData(), guide, &scene.mediumHoldouts);
    rec.cameraFlightEnded(walk.reachedEnd);
    rec.recordFlightEmission();
    for (int k = 0; walk.chosen && nee && k < kScatterPoints; ++k)
        rec.litInMedium(throughput.beta * walk.weight[k],
                        directLightMedium(scene, walk.collision[k], -path.ray.d, sampler, ts),
                        walk.collision[k].t);
    throughput.beta *= walk.T;
    const bool plate = walk.reachedEnd && (!ahead.hit || rec.holdout(*scene.geometry, *ahead.hit));
    rec.coverage(plate, walk.T.average(), walk.holdoutCoverage);
    return walk.reachedEnd;
}

const Material& gatherAtSurface(const RenderScene& scene, const SurfaceHit& hit, bool nee,
                                Sampler& sampler, ThreadState& ts, CameraPath& path,
                                PathRecorder& rec) {
    const Material& mat = scene.geometry->materialAt(hit);
    const SampledSpectrum& beta = path.throughput.beta;
    // Past a surface, escapes no longer see the lights at infinity for a medium vertex: its
    // shadow rays could not have crossed glass, nor any surface.
    path.escapePdf = 0.f;
    // An emitter next-event estimation samples was counted at the vertex before, unless the
    // path came straight from the camera or through mirrors and glass (no shadow ray there).
    if (mat.emissive() && (path.specularChain || !sampledEmitter(scene, hit.shape)))
        rec.emittedAtSurface(beta * mat.emission(path.wavelengths), hit.t);
    if (mat.specular()) {
        rec.passedSpecular(hit.t);
        return mat;
    }
    if (nee)
        rec.litAtSurface(beta, directLightSurface(scene, hit, mat, -path.ray.d, sampler, ts),
                         hit.t);
    rec.scatteredAtSurface(hit.t);
    path.specularChain = false;
    return mat;
}

void escapeToDome(const RenderScene& scene, const CameraPath& path, ThreadState& ts,
                  PathRecorder& rec) {
    if (!std::isinf(path.ray.tMax)) return;
    if (path.specularChain)
        rec.escaped(path.throughput.beta *
                    escapedRadiance(scene, path.ray.d, path.wavelengths, path.depth == 0));
    else if (path.escapePdf > 0.f)
        rec.litByEscape(path.throughput.beta * path.escapeShare,
                        skyAtEscape(scene, path.ray, path.escapePdf, path.escapeSkyRate,
                                    path.wavelengths, ts));
}

}  // namespace mirage
