// One frame of the render pipeline, shared by `mirage render` and `mirage tradeoff` so that the
// instrument measures exactly what the renderer does: command-line settings onto a loaded scene,
// then integrator → photon pass (preprocess) → render → develop.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/clock.h"
#include "film/film.h"
#include "render/integrator.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace mirage {

class ColorPipeline;

// Command-line settings that override a loaded scene's (zero/empty/negative: keep the scene's).
struct FrameSettings {
    std::string resolution;  // WxH
    int spp = 0;
    int64_t seed = -1;
    bool quiet = false;
    std::vector<std::string> aovs;  // --aov: passes added to [output] aovs
};

// Applies `cli` to `scene`; `input` is the scene's path (a bare VDB keeps its automatic camera
// framed for a new aspect ratio). Throws MirageError for a malformed --resolution.
void applyFrameSettings(Scene& scene, const std::string& input, const FrameSettings& cli);

// `--quality draft|preview|final`: points on the measured speed↔accuracy curves
// (docs/performance.md, "Quality presets"). The photon integrator takes spp, photons and k; the
// others spp only.
struct QualityPreset {
    std::string name;
    int spp = 0;            // photon integrator: samples per pixel
    uint64_t photons = 0;   // photon integrator: photons emitted
    int k = 0;              // photon integrator: photons per estimate
    int pathSpp = 0;        // single / volpath: samples per pixel
    double sceneScale = 1;  // × the samples and photons a scene states (Scene::statedSpp)
    // × the passes `auto` made of film.spp on dense smoke (Scene::autoSet): measured on the
    // race scene, where one pass in 16 is the draft's error.
    double autoPassScale = 1;
};
const std::vector<QualityPreset>& qualityPresets();
// Throws MirageError naming the presets for an unknown name.
const QualityPreset& qualityPreset(const std::string& name);
// Sets the preset's values on `scene` for `integrator`, except the keys that an explicit
// --set in `overrides` names (film.spp, render.photons, render.k): those win, and so does a k
// the scene file states (the bandwidth its author chose). Where the scene file states
// film.spp or render.photons, that is what the scene needs for a clean picture
// (the preview preset) and the preset scales it (draft ¼, preview 1, final 4: the final
// preset is the 4× render the noise checks compare against); elsewhere the preset's own
// measured values apply. A curved-camera scene that asks for 16 samples gets 4, 16 or 64. A
// stated render.k is kept at every preset. A scene in passes (stated, or made by `auto` on
// dense smoke) has its passes scaled, each keeping its photon map's photons; auto's passes
// by their own measured scale (draft 1/16, preview 1, final 4).
void applyQualityPreset(Scene& scene, const QualityPreset& preset, const std::string& integrator,
                        const std::vector<std::string>& overrides);

struct RenderedFrame {
    Image image;  // developed, in the working space
    RenderStats stats;
    std::unique_ptr<Film> film;              // the sums behind `image` (partial files)
    std::unique_ptr<DeepFilm> deep;          // deep samples (working space), when asked for
    std::unique_ptr<Integrator> integrator;  // for its name, summary and capped paths
    double seconds = 0;                // wall: integrator set-up, photon pass, render, develop
    std::optional<PassReport> passes;  // a render in passes (scene.passes.enabled())
};

// The photon integrator's settings for `scene`: its [render] photon keys, the render's seed and
// progress mode, and its [refraction] field (the photon pass of `render` and `mirage photons`).
PhotonIntegratorSettings photonSettingsFor(const Scene& scene);

// Renders `scene` with `integrator` ("" = the scene's own, "auto" = chooseIntegrator's) and
// develops it through `color`: one render of film.spp samples, or, when scene.passes asks, a
// render in passes (render/passes.h). `checkpoint` / `passCheckpoint` (optional) resume from
// and checkpoint to a partial file, tile by tile (renderer.h) or pass by pass (passes.h).
RenderedFrame renderFrame(const Scene& scene, const std::string& integrator,
                          const ColorPipeline& color, TileCheckpoint* checkpoint = nullptr,
                          PassCheckpoint* passCheckpoint = nullptr);

}  // namespace mirage
