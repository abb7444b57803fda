// Single scattering + emission along the camera ray, by null-collision tracking.
//
// Along the camera ray, the radiance is L = ∫ T(t) [σa Le + σs Σ_lights ∫ p Li T_l] dt.
// The flight is followed to its end by ratio tracking (transport/scatter_point.h): tentative
// collisions at rate σ̄, the transmittance T multiplied by σn/σ̄ at each. Emission is scored at
// every tentative collision, β T σa Le / σ̄ (a collision estimator of ∫ T σa Le dt); the
// scattering points (kScatterPoints of them) are chosen among the tentative collisions
// ∝ T σs g by systematic resampling (g: a coarse guess of the light there, filled once per
// frame, render/scatter_guide_build.h), and each scores its weight times the direct light
// (next-event estimation with a residual-ratio-tracked shadow ray). No sample escapes or is
// absorbed with a score of 0, as one stopped at its first real collision would. T at the end
// estimates the transmittance of the flight: 1 − T is the pixel's coverage (alpha), and β T the
// throughput that reaches a surface behind the medium.
//
// Surfaces: the camera ray's flight ends at the nearest surface. A diffuse surface scores its
// emission and its direct light (NEE through the media, blocked by surfaces) and ends the path:
// one bounce, as a medium event. A mirror or glass surface is followed (continueAtSurface, up
// to kMaxSpecularBounces), so the first diffuse or medium event may be seen through glass. A
// dispersive dielectric keeps the hero wavelength only, as in volpath.cpp. A ray that leaves the
// scene sees the lights at infinity (the dome), which no next-event estimate has counted on it.
//
// Curved light: behind the curved camera (render/curved_camera.h) the camera ray is a chord of
// its Fermat path, and the shadow rays towards lights at infinity bend too
// (render/direct_light.cpp); a mirror's or glass's continuation stays straight.
#include <memory>

#include "render/camera_path.h"
#include "render/integrator.h"
#include "render/scatter_guide_build.h"
#include "transport/path_vertex.h"

namespace mirage {

namespace {

class SingleScatterIntegrator : public Integrator {
public:
    explicit SingleScatterIntegrator(bool directLight) : mDirect(directLight) {}
    const IntegratorInfo& info() const override { return integratorInfo("single"); }
    bool lightShapedRadiance() const override { return true; }
    using Integrator::preprocess;
    void preprocess(const RenderScene& scene, uint64_t frameSamples) override {
        mGuide = mDirect ? buildScatterGuide(scene, frameSamples) : nullptr;
    }

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        PathRecorder rec(&out, ts);
        CameraPath path(cameraRay, w);
        for (;; ++path.depth) {
            const SurfaceAhead ahead = surfaceAhead(scene, path.ray);
            if (!scatterAlongFlight(scene, ahead, mGuide.get(), mDirect, sampler, ts, path, rec))
                break;
            if (!ahead.hit) {
                escapeToDome(scene, path, ts, rec);
                break;
            }
            // A holdout is seen as nothing: nothing of its own, nothing behind it.
            const SurfaceHit& hit = *ahead.hit;
            if (rec.holdout(*scene.geometry, hit) || path.depth >= kMaxSpecularBounces) break;
            // The surface: emission and direct light where it is diffuse, else follow the mirror
            // or glass.
            const Material& mat = gatherAtSurface(scene, hit, mDirect, sampler, ts, path, rec);
            if (!mat.specular() || !continueAtSurface(mat, hit, path.wavelengths,
                                                      TransportMode::Radiance, sampler, &path))
                break;
        }
        rec.finish(path.throughput);
        return out;
    }

private:
    bool mDirect;
    std::unique_ptr<ScatterGuide> mGuide;  // null: points ∝ T σs
};

}  // namespace

std::unique_ptr<Integrator> makeSingleScatterIntegrator(bool directLight) {
    return std::make_unique<SingleScatterIntegrator>(directLight);
}

}  // namespace mirage
