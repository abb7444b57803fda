// The default integrator (`[render] integrator = "auto"`): the method that renders all the light
// of this scene and converges fastest, with the reason `mirage info` and the render summary give.
//
// The rules, in order, each a case where one method sees light the others miss or converges
// faster (docs/performance.md, "The default integrator"):
//  1. Light bends inside the scene ([refraction] with photonsCurve): straight shadow rays and
//     straight scattered paths are no paths of light there; only photons follow Fermat paths
//     (Gutierrez et al. 2005), so `photon`.
//  2. A mirror or glass surface and a light: light reaching a diffuse surface or a medium
//     through a specular chain (caustics, L S+ D, and volume caustics) has no shadow ray and,
//     the lights being delta or not hit by paths, no path from the camera either; the photon
//     maps hold it, so `photon`.
//  3. Nothing scatters and there are no surfaces: emission and absorption are the whole answer,
//     and `single` computes them exactly without any scattered path.
//  4. Otherwise `volpath`: unbiased, every bounce. Since the voxel majorant the progressive
//     photon mapper reaches a given error sooner on the race scene (dense, albedo 0.95: about
//     a third of volpath's time, docs/performance.md), but it is biased at any finite pass count
//     and the shipped scenes' presets were measured with volpath; when to prefer it is still
//     to be settled.
#include "scene/scene.h"

namespace mirage {

namespace {

bool anyScattering(const RenderScene& render) {
    for (const auto& medium : render.media)
        for (const auto& c : medium->shader().components)
            if (c.sigmaS.maxValue() > 0) return true;
    return false;
}

// The first specular material's index, or -1.
int firstSpecularMaterial(const RenderScene& render) {
    if (!render.hasSurfaces()) return -1;
    const GeometryScene& g = *render.geometry;
    for (size_t i = 0; i < g.materialCount(); ++i)
        if (g.material(int(i)).specular()) return int(i);
    return -1;
}

}  // namespace

IntegratorChoice chooseIntegrator(const Scene& scene) {
    const RenderScene& render = scene.render;
    if (scene.refraction && photonsCurve(scene.refraction->field.get(), render.bounds()))
        return {"photon",
                "light bends inside the scene ([refraction]): only photons follow curved light "
                "paths (straight shadow rays and scattered paths do not)"};
    const bool lit = !render.lights.empty();
    if (lit && firstSpecularMaterial(render) >= 0)
        return {"photon",
                "a mirror or glass surface and a light: caustics through specular chains come "
                "from the photon maps only"};
    if (!anyScattering(render) && !render.hasSurfaces())
        return {"single",
                "nothing scatters and there are no surfaces: emission and absorption are the "
                "whole answer, which single computes exactly"};
    return {"volpath",
            std::string(anyScattering(render) ? "media scatter" : "surfaces reflect") +
                ": the unbiased path tracer renders every bounce (on dense, bright smoke "
                "--integrator photon --passes N can reach a given error sooner)"};
}

void resolveAutoIntegrator(Scene* scene) {
    if (scene->integrator != "auto") return;
    IntegratorChoice choice = chooseIntegrator(*scene);
    scene->integrator = choice.name;
    scene->integratorWhy = "auto: " + choice.why;
}

}  // namespace mirage
