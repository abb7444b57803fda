// Single scattering + emission by null-collision tracking.
//
// Along the camera ray, the radiance is L = ∫ T(t) [σa Le + σs Σ_lights ∫ p Li T_l] dt.
// Tentative collisions come at rate σ̄. At each one:
//  - emission is scored at every tentative collision, β σa Le / σ̄ (a collision estimator
//    whose expectation is ∫ T σa Le dt);
//  - then an event is chosen with the probabilities of eventProbabilities(): absorption ends
//    the path, real scattering scores β σs/(σ̄ P_s) · (direct light) and ends it (single
//    scattering), a null collision multiplies β by σn/(σ̄ P_n) and continues.
// β is 1 at every wavelength for grey media; Russian roulette (PathThroughput::roulette) keeps
// long spectral walks short.
// The probability of leaving the medium is T, so β at escape estimates the transmittance and
// 1 − β is the pixel's coverage (alpha).
//
// Surfaces: the camera ray's flight ends at the nearest surface. A diffuse surface scores its
// emission and its direct light (NEE through the media, blocked by surfaces) and ends the path:
// one bounce, as a medium event. A mirror or glass surface is followed (continueAtSurface, up
// to kMaxSpecularBounces), so the first diffuse or medium event may be seen through glass. A
// dispersive dielectric keeps the hero wavelength only, as in volpath.cpp.
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
    std::string name() const override { return "single"; }

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
                chooseScatterPoint(ts.tracking, ray, tEnd, path.beta, sampler, &out.L);
            if (walk.chosen && mDirect)
                out.L += path.beta * walk.weight *
                         directLightMedium(scene, walk.collision, -ray.d, sampler, ts);
            const bool escaped = walk.reachedEnd;
            path.beta *= walk.T;
            if (bounce == 0)
                out.alpha = escaped && !hit ? clamp(1.f - walk.T.average(), 0.f, 1.f) : 1.f;
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
