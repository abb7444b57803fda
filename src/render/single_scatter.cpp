// Single scattering + emission along the camera ray, by null-collision tracking.
//
// Along the camera ray, the radiance is L = ∫ T(t) [σa Le + σs Σ_lights ∫ p Li T_l] dt.
// The flight is followed to its end by ratio tracking (transport/scatter_point.h): tentative
// collisions at rate σ̄, the transmittance T multiplied by σn/σ̄ at each. Emission is scored at
// every tentative collision, β T σa Le / σ̄ (a collision estimator of ∫ T σa Le dt); the
// scattering points (kScatterPoints of them) are chosen among the tentative collisions
// ∝ T σs g by systematic resampling (g: the guide's guess of the light there, filled once per
// frame, transport/scatter_guide.h), and each scores its weight times the direct light
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
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "render/direct_light.h"
#include "render/integrator.h"
#include "transport/path_vertex.h"
#include "transport/scatter_point.h"

namespace mirage {

namespace {

// Shadow rays per light and cell (ratio tracking's estimate of one is 0 where rouletted), and
// the guide's floor as a share of its largest value: a cell guessed dark still holds points,
// at most 1/kGuideFloor times fewer than the light's brightest, so that where the coarse guess
// is wrong (a lit edge inside a dark cell) no rare point carries a huge weight. Measured on
// the race scene (docs/performance.md): floors of 10⁻³ and 0.2 gave 2.2× and 1.2× the relMSE
// of 0.05; 8 or 16 estimates per cell no less than 4.
constexpr int kGuideEstimates = 4;
constexpr float kGuideFloor = 0.05f;
constexpr uint64_t kGuideCollisions = 1024;

// The guide of the scattering points (transport/scatter_guide.h): at each cell's centre, the
// direct light it would receive, one light sample and kGuideEstimates shadow rays per light
// (surfaces ignored), at the middle of the visible range. A pure function of the scene: the
// guide, and so the image, is the same for any thread count.
std::unique_ptr<ScatterGuide> buildGuide(const RenderScene& scene) {
    Bounds3 bounds;
    for (const auto& m : scene.media) bounds.expand(m->worldBounds());
    // No guide for unbounded media (a fog filling the scene): no grid to lay over them.
    const Vec3 d = bounds.diagonal();
    if (scene.lights.empty() || bounds.empty() ||
        !(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z)))
        return nullptr;
    TrackingContext ctx(scene.mediaPointers());
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.5f);
    ctx.setWavelengths(w);
    // A guess needs no accuracy (any g > 0 keeps the estimate unbiased), but its cost must stay
    // bounded: a shadow ray cut at kGuideCollisions tentative collisions counts as dark and
    // takes the floor. Without the cut, a grid of huge voxels (σ ~ 10⁶/m in a coarse majorant
    // cell) sends each of the guide's 131 k rays to the render's cap of 65 536 collisions.
    // 1024 leaves the race scene's guide as it was (some of its rays need more than 256) and
    // holds the guide of tests/physics' degenerate grids to seconds.
    ctx.maxCollisions = kGuideCollisions;
    Sampler sampler(SamplerKind::Random, 0x6775696465ull, 0, 0);  // "guide"
    constexpr int n = ScatterGuide::kResolution;
    std::vector<float> values(size_t(n) * n * n, 0.f);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Vec3 p = ScatterGuide::cellCentre(bounds, i, j, k);
                float g = 0.f;
                for (const auto& light : scene.lights) {
                    LightSample ls;
                    if (!light->sampleLi(p, 0.5f, 0.5f, w, &ls)) continue;
                    const Ray shadow{p, ls.wi, ls.distance};
                    for (int e = 0; e < kGuideEstimates; ++e)
                        g += (transmittance(ctx, shadow, ls.distance, sampler) * ls.Li).average() /
                             float(kGuideEstimates);
                }
                values[size_t((k * n + j) * n + i)] = std::isfinite(g) ? std::max(g, 0.f) : 0.f;
            }
    return std::make_unique<ScatterGuide>(bounds, std::move(values), kGuideFloor);
}

class SingleScatterIntegrator : public Integrator {
public:
    explicit SingleScatterIntegrator(bool directLight) : mDirect(directLight) {}
    const IntegratorInfo& info() const override { return integratorInfo("single"); }
    bool lightShapedRadiance() const override { return true; }
    // The guide is built by the first sample of the frame (timed with the render), from the
    // frame's scene; without preprocess (a caller driving Li alone) there is none.
    void preprocess(const RenderScene&) override {
        mGuide.reset();
        mGuideOnce = std::make_unique<std::once_flag>();
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
        if (mDirect && mGuideOnce) std::call_once(*mGuideOnce, [&] { mGuide = buildGuide(scene); });
        for (int bounce = 0;; ++bounce) {
            std::optional<SurfaceHit> hit;
            if (geometry) hit = geometry->intersect(ray);
            const float tEnd = hit ? hit->t : ray.tMax;
            // The scattering point along the whole flight (transport/scatter_point.h). The
            // walk scores emission straight into the beauty, or, with passes or deep output,
            // apart per collision, to be tagged and placed.
            const bool split = out.aov || out.deep;
            ts.emitted.clear();
            const ScatterPointWalk walk = chooseScatterPoints(
                ts.tracking, ray, tEnd, path.beta, sampler, split ? nullptr : &out.L,
                split ? &ts.emitted : nullptr, mGuide.get());
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
    mutable std::unique_ptr<std::once_flag> mGuideOnce;
    mutable std::unique_ptr<ScatterGuide> mGuide;  // null: points ∝ T σs
};

}  // namespace

std::unique_ptr<Integrator> makeSingleScatterIntegrator(bool directLight) {
    return std::make_unique<SingleScatterIntegrator>(directLight);
}

}  // namespace mirage
