// Single scattering + emission along the camera ray, by null-collision tracking.
//
// Along the camera ray, the radiance is L = ∫ T(t) [σa Le + σs Σ_lights ∫ p Li T_l] dt.
// The flight is followed to its end by ratio tracking (transport/scatter_point.h): tentative
// collisions at rate σ̄, the transmittance T multiplied by σn/σ̄ at each. Emission is scored at
// every tentative collision, β T σa Le / σ̄ (a collision estimator of ∫ T σa Le dt); the
// scattering points (kScatterPoints of them) are chosen among the tentative collisions ∝ T σs
// by systematic resampling, and each scores its weight times the direct light (next-event
// estimation with a residual-ratio-tracked shadow ray). No sample escapes or is absorbed with
// a score of 0, as one stopped at its first real collision would.
// T at the end estimates the transmittance of the flight: 1 − T is the pixel's coverage
// (alpha), and β T the throughput that reaches a surface behind the medium.
//
// Surfaces: the camera ray's flight ends at the nearest surface. A diffuse surface scores its
// emission and its direct light (NEE through the media, blocked by surfaces) and ends the path:
// one bounce, as a medium event. A mirror or glass surface is followed (continueAtSurface, up
// to kMaxSpecularBounces), so the first diffuse or medium event may be seen through glass. A
// dispersive dielectric keeps the hero wavelength only, as in volpath.cpp. A ray that leaves the
// scene sees the lights at infinity (the dome), which no next-event estimate has counted on it.
#include <cmath>
#include <optional>

#include "render/direct_light.h"
#include "render/integrator.h"
#include "transport/path_vertex.h"
#include "transport/scatter_point.h"

namespace mirage {

namespace {

class SingleScatterIntegrator : public Integrator {
public:
    explicit SingleScatterIntegrator(bool directLight) : mDirect(directLight) {}
    const IntegratorInfo& info() const override { return integratorInfo("single"); }
    bool lightShapedRadiance() const override { return true; }

    RadianceSample Li(const RenderScene& scene, const Ray& cameraRay, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        RadianceSample out;
        PathThroughput path;
        const GeometryScene* geometry = scene.hasSurfaces() ? scene.geometry.get() : nullptr;
        Ray ray = cameraRay;
        for (int bounce = 0;; ++bounce) {
            std::optional<SurfaceHit> hit;
            if (geometry) hit = geometry->intersect(ray);
            const float tEnd = hit ? hit->t : ray.tMax;
            // The scattering point along the whole flight (transport/scatter_point.h).
            const ScatterPointWalk walk =
                chooseScatterPoints(ts.tracking, ray, tEnd, path.beta, sampler, &out.L);
            for (int k = 0; walk.chosen && mDirect && k < kScatterPoints; ++k)
                out.L += path.beta * walk.weight[k] *
                         directLightMedium(scene, walk.collision[k], -ray.d, sampler, ts);
            const bool escaped = walk.reachedEnd;
            path.beta *= walk.T;
            if (bounce == 0)
                out.alpha = escaped && !hit ? clamp(1.f - walk.T.average(), 0.f, 1.f) : 1.f;
            // Leaving the scene: the dome, seen through the media (camera ray or after glass).
            if (escaped && !hit && std::isinf(ray.tMax))
                out.L += path.beta * escapedRadiance(scene, ray.d, w, bounce == 0);
            if (!escaped || !hit || bounce >= kMaxSpecularBounces) break;

            // The surface: emission and direct light where it is diffuse, else follow the mirror
            // or glass.
            const Material& mat = geometry->materialAt(*hit);
            if (mat.emissive()) out.L += path.beta * mat.emission(w);
            if (!mat.specular()) {
                if (mDirect)
                    out.L += path.beta * directLightSurface(scene, *hit, mat, -ray.d, sampler, ts);
                break;
            }
            Ray next;
            if (!continueAtSurface(mat, *hit, ray.d, w, TransportMode::Radiance, sampler, &path,
                                   &next))
                break;
            ray = next;
        }
        out.L = path.estimate(out.L);
        return out;
    }

private:
    bool mDirect;
};

}  // namespace

std::unique_ptr<Integrator> makeSingleScatterIntegrator(bool directLight) {
    return std::make_unique<SingleScatterIntegrator>(directLight);
}

}  // namespace mirage
