// The steps camera estimators share (camera_path.h says which and why).
#include "render/camera_path.h"

#include <cmath>

#include "render/direct_light.h"

namespace mirage {

SurfaceAhead surfaceAhead(const RenderScene& scene, const Ray& ray) {
    SurfaceAhead ahead;
    if (scene.hasSurfaces()) ahead.hit = scene.geometry->intersect(ray);
    ahead.tEnd = ahead.hit ? ahead.hit->t : ray.tMax;
    return ahead;
}

const Material& gatherAtSurface(const RenderScene& scene, const SurfaceHit& hit, bool nee,
                                Sampler& sampler, ThreadState& ts, CameraPath& path,
                                PathRecorder& rec) {
    const Material& mat = scene.geometry->materialAt(hit);
    const SampledSpectrum& beta = path.throughput.beta;
    if (mat.emissive()) rec.emittedAtSurface(beta * mat.emission(path.wavelengths), hit.t);
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

void escapeToDome(const RenderScene& scene, const CameraPath& path, PathRecorder& rec) {
    if (!path.specularChain || !std::isinf(path.ray.tMax)) return;
    rec.escaped(path.throughput.beta *
                escapedRadiance(scene, path.ray.d, path.wavelengths, path.depth == 0));
}

}  // namespace mirage
