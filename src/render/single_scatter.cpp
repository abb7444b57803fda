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
#include <cmath>
#include <memory>
#include <optional>

#include "render/camera_ray_data.h"
#include "render/direct_light.h"
#include "render/integrator.h"
#include "render/scatter_guide_build.h"
#include "transport/path_vertex.h"
#include "transport/scatter_point.h"

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
        out.aov = ts.aov;
        out.deep = ts.deep;
        PathThroughput path;
        DeepView view;
        const GeometryScene* geometry = scene.hasSurfaces() ? scene.geometry.get() : nullptr;
        Ray ray = cameraRay;
        for (int bounce = 0;; ++bounce) {
            std::optional<SurfaceHit> hit;
            if (geometry) hit = geometry->intersect(ray);
            const float tEnd = hit ? hit->t : ray.tMax;
            // The scattering point along the whole flight (transport/scatter_point.h). The
            // walk scores emission straight into the beauty, or, with passes or deep output,
            // apart per collision, to be tagged and placed.
            const bool split = out.aov || out.deep;
            ts.emitted.clear();
            // The camera ray's walk is the data passes' too (render/camera_ray_data.h).
            CameraRayData* data = bounce == 0 ? ts.cameraData : nullptr;
            const ScatterPointWalk walk = chooseScatterPoints(
                ts.tracking, ray, tEnd, path.beta, sampler, split ? nullptr : &out.L,
                split ? &ts.emitted : nullptr, data, mGuide.get(), &scene.mediumHoldouts);
            if (data) data->walked(walk.reachedEnd);
            for (const EmissionAt& e : ts.emitted)
                out.add(e.L, path.history.emitted(), kEmissionGroup,
                        view.at(path.history, e.t, false));
            for (int k = 0; walk.chosen && mDirect && k < kScatterPoints; ++k)
                out.addLit(path.beta * walk.weight[k],
                           directLightMedium(scene, walk.collision[k], -ray.d, sampler, ts),
                           path.history.gathered(false), ts.lightSplit,
                           view.at(path.history, walk.collision[k].t, false));
            const bool escaped = walk.reachedEnd;
            path.beta *= walk.T;
            // A holdout is seen as nothing: what lies in front of it covers the pixel, and
            // nothing of its own does (docs/aovs.md, "Holdouts").
            const bool holdout = hit && geometry->holdout(*hit);
            if (bounce == 0)
                out.alpha = clamp((escaped && (!hit || holdout) ? 1.f - walk.T.average() : 1.f) -
                                      walk.holdoutCoverage,
                                  0.f, 1.f);
            // Leaving the scene: the dome, seen through the media (camera ray or after glass).
            // Light seen straight from its source, as emission is: the emission pass and
            // lightgroup_emission (docs/aovs.md).
            if (escaped && !hit && std::isinf(ray.tMax))
                out.add(path.beta * escapedRadiance(scene, ray.d, w, bounce == 0),
                        path.history.emitted(), kEmissionGroup, kUnplaced);
            if (!escaped || !hit || holdout || bounce >= kMaxSpecularBounces) break;

            // The surface: emission and direct light where it is diffuse, else follow the mirror
            // or glass.
            const Material& mat = geometry->materialAt(*hit);
            const DeepAt at = view.at(path.history, hit->t, true);
            if (mat.emissive())
                out.add(path.beta * mat.emission(w), path.history.emitted(), kEmissionGroup, at);
            if (!mat.specular()) {
                if (mDirect)
                    out.addLit(path.beta, directLightSurface(scene, *hit, mat, -ray.d, sampler, ts),
                               path.history.gathered(true), ts.lightSplit, at);
                break;
            }
            view.specular(path.history, hit->t);
            Ray next;
            if (!continueAtSurface(mat, *hit, ray.d, w, TransportMode::Radiance, sampler, &path,
                                   &next))
                break;
            ray = next;
        }
        out.finish(path);
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
