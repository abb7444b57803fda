// The default integrator (`[render] integrator = "auto"`): the method that renders all the light
// of this scene and converges fastest, with the reason `mirage info` and the render summary give.
//
// The rules, in order, each a case where one method sees light the others miss or converges
// faster (docs/performance.md, "The default integrator"):
//  1. Light bends inside the scene ([refraction] with photonsCurve): photons follow every
//     Fermat path (Gutierrez et al. 2005), from lamps too. Behind the curved camera `single`
//     and `volpath` bend their scattered paths and their shadow rays to lights at infinity (the
//     sun, a dome; render/curved_transport.h), but a shadow ray to a lamp at a finite distance
//     (point, spot, sphere, quad) stays straight, and `[refraction] curved_transport = false`
//     keeps all of them straight; so `photon`.
//  2. A mirror or glass surface and a light: light reaching a diffuse surface or a medium
//     through a specular chain (caustics, L S+ D, and volume caustics) has no shadow ray and,
//     the lights being delta or not hit by paths, no path from the camera either; the photon
//     maps hold it, so `photon`.
//  3. Nothing scatters and there are no surfaces: emission and absorption are the whole answer,
//     and `single` computes them exactly without any scattered path.
//  4. Dense, bright, grey smoke: every medium grey with single-scattering albedo ≥ 0.9 and a
//     typical optical depth ≥ 10 (below), no surfaces or emission, lights of at most three
//     colours (the film's exact colour, render/achromatic_film.h). Most of the light there has
//     scattered many times, smoothly, and the progressive photon mapper reuses each photon
//     across pixels: on the race's three caches it reaches Cycles' 4-, 16- and 64-sample
//     errors in 0.1–0.3 of volpath's time (docs/performance-history.md, "The default on dense
//     smoke"). `photon` then renders the scene's samples as progressive passes of pass_spp
//     samples, a photon map each (render/passes.h), so that longer renders keep converging;
//     unless the scene states them, one sample a pass and k = 32 (resolveAutoIntegrator).
//  5. Otherwise `volpath`: unbiased, every bounce.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/achromatic_film.h"
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

// The lowest single-scattering albedo σs/(σa + σs) of the medium's components (grey media:
// one value each).
float lowestAlbedo(const Medium& medium) {
    float lowest = 1.f;
    for (const auto& c : medium.shader().components) {
        const float s = c.sigmaS.maxValue(), t = c.sigmaA.maxValue() + s;
        if (t > 0.f) lowest = std::min(lowest, s / t);
    }
    return lowest;
}

// The optical depth of a typical chord through the smoke: the mean majorant σ̄ (1/m) over the
// cells that hold any medium, times the cube root of their volume (m, the object-to-world
// scale applied). An upper bound of the mean σt (the majorant bounds it), measured on what the
// tracking itself uses, at no cost beyond one sweep of the majorant grid.
float typicalOpticalDepth(const Medium& medium) {
    const MajorantGrid& g = medium.majorant();
    double sum = 0;
    size_t occupied = 0;
    for (int z = 0; z < g.res(2); ++z)
        for (int y = 0; y < g.res(1); ++y)
            for (int x = 0; x < g.res(0); ++x)
                if (const float v = g.cell(x, y, z); v > 0.f) {
                    sum += v;
                    ++occupied;
                }
    if (occupied == 0) return 0.f;
    const Vec3 d = g.bounds().diagonal();
    const double cellVolume = double(d.x) * d.y * d.z / (double(g.res(0)) * g.res(1) * g.res(2));
    const double scale = std::cbrt(std::abs(medium.objectToWorld().linear.determinant()));
    return float(sum / double(occupied) * std::cbrt(double(occupied) * cellVolume) * scale);
}

bool emits(const RenderScene& render) {
    for (const auto& medium : render.media)
        if (medium->emissive()) return true;
    return false;
}

// A dome lights the scene. Its photons enter through a disc facing the scene from every
// direction, and in a bright cloud under a white sky the photon mapper given 13 s reached a
// relMSE of 0.52 where volpath's 9.3 s reached 0.048 (issue 33's sky regime): domes keep volpath.
bool domeLit(const RenderScene& render) {
    for (const auto& light : render.lights)
        if (light->infinite()) return true;
    return false;
}

constexpr float kDenseAlbedo = 0.9f;
constexpr float kDenseOpticalDepth = 10.f;
constexpr int kProgressivePassSpp = 1;
constexpr int kProgressiveK = 32;
// The first pass traces photons / this (docs/performance-history.md, "A smaller first pass").
constexpr uint64_t kProgressiveFirstPassShare = 5;

// Rule 4's scene: its reason, or "" when the scene is not one.
std::string denseBrightSmoke(const RenderScene& render) {
    std::string colour;
    if (render.media.empty() || render.hasSurfaces() || emits(render) || domeLit(render) ||
        sampledColour(render, integratorInfo("photon"), &colour))
        return "";
    float albedo = 1.f, depth = kInfinity;
    for (const auto& medium : render.media) {
        albedo = std::min(albedo, lowestAlbedo(*medium));
        depth = std::min(depth, typicalOpticalDepth(*medium));
    }
    if (albedo < kDenseAlbedo || depth < kDenseOpticalDepth) return "";
    char why[200];
    std::snprintf(why, sizeof why,
                  "dense, bright, grey smoke (albedo %.2f, typical optical depth %.0f): "
                  "progressive photon passes reach a given error sooner than volpath",
                  double(albedo), double(depth));
    return why;
}

}  // namespace

IntegratorChoice chooseIntegrator(const Scene& scene) {
    const RenderScene& render = scene.render;
    if (scene.refraction && photonsCurve(scene.refraction->field.get(), render.bounds()))
        return {"photon",
                "light bends inside the scene ([refraction]): photons follow every curved "
                "path, from lamps too; single and volpath bend shadow rays to the sun and a "
                "dome only, those to lamps stay straight"};
    const bool lit = !render.lights.empty();
    if (lit && firstSpecularMaterial(render) >= 0)
        return {"photon",
                "a mirror or glass surface and a light: caustics through specular chains come "
                "from the photon maps only"};
    if (!anyScattering(render) && !render.hasSurfaces())
        return {"single",
                "nothing scatters and there are no surfaces: emission and absorption are the "
                "whole answer, which single computes exactly"};
    if (lit)
        if (std::string why = denseBrightSmoke(render); !why.empty()) return {"photon", why, true};
    return {"volpath", std::string(anyScattering(render) ? "media scatter" : "surfaces reflect") +
                           ": the unbiased path tracer renders every bounce"};
}

void resolveAutoIntegrator(Scene* scene) {
    // Undo what the previous choice set: a named integrator takes film.spp, pass_spp and k
    // again as the scene states them.
    Scene::AutoProgressive& set = scene->autoSet;
    if (set.passes) {
        scene->statedPasses = 0;
        scene->passes.maxPasses = 0;
    }
    if (set.passSpp) scene->passes.sppPerPass = PassSettings{}.sppPerPass;
    if (set.k) scene->photon.k = 0;
    if (set.firstPassPhotons) scene->photon.firstPassPhotons = 0;
    set = {};
    if (scene->integrator != "auto") return;
    IntegratorChoice choice = chooseIntegrator(*scene);
    scene->integrator = choice.name;
    scene->integratorWhy = "auto: " + choice.why;
    if (!choice.progressive) return;
    // Rule 4's settings where the scene leaves them open (measured on the race scene,
    // docs/performance-history.md "Passes of one sample"): a pass's error is mostly its photon
    // map's, its time mostly its camera samples', so one sample a pass; and k = 32 nearest
    // photons, whose wider discs halve a map's noise for 13 % more time.
    if (scene->statedPassSpp == 0) {
        scene->passes.sppPerPass = kProgressivePassSpp;
        set.passSpp = true;
    }
    if (scene->photon.k == 0 && scene->photon.estimate == PhotonEstimate::Beam) {
        scene->photon.k = kProgressiveK;
        set.k = true;
    }
    if (!scene->statedFirstPassPhotons) {
        scene->photon.firstPassPhotons =
            std::max<uint64_t>(1, scene->photon.photons / kProgressiveFirstPassShare);
        set.firstPassPhotons = true;
    }
    if (scene->statedPasses == 0) {
        // film.spp as passes of pass_spp samples, a photon map each; --spp, --passes, the
        // time and noise targets and --quality treat them as passes the scene stated.
        const int k = scene->passes.sppPerPass;
        scene->statedPasses = std::max(1, (scene->settings.spp + k - 1) / k);
        scene->passes.maxPasses = scene->statedPasses;
        set.passes = true;
    }
    char why[200];
    std::snprintf(why, sizeof why, "; passes of %d spp, a photon map of %llu photons each",
                  scene->passes.sppPerPass, (unsigned long long)scene->photon.photons);
    scene->integratorWhy += why;
    const uint64_t first = scene->photon.photonsOfPass(0);
    if (first != scene->photon.photons) {
        std::snprintf(why, sizeof why, " (the first %llu)", (unsigned long long)first);
        scene->integratorWhy += why;
    }
    std::snprintf(why, sizeof why, ", k %d", scene->photon.kOrDefault());
    scene->integratorWhy += why;
}

}  // namespace mirage
