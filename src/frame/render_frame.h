// One frame of the render pipeline, shared by `mirage render`, `mirage tradeoff` (so that the
// instrument measures exactly what the renderer does) and a program that renders in code:
// integrator → photon pass (preprocess) → render → develop, for a scene loaded with its frame
// request applied (frame_load.h).
#pragma once

#include <memory>
#include <optional>

#include "core/clock.h"
#include "film/deep.h"
#include "film/film.h"
#include "render/integrator.h"
#include "render/passes.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace mirage {

class CancelToken;
class ColorPipeline;

struct RenderedFrame {
    Image image;  // developed, in the working space
    RenderStats stats;
    std::unique_ptr<Film> film;              // the sums behind `image` (partial files)
    std::unique_ptr<DeepFilm> deep;          // deep samples (working space), when asked for
    std::unique_ptr<Integrator> integrator;  // for its name, summary and capped paths
    double seconds = 0;                // wall: integrator set-up, photon pass, render, develop
    std::optional<PassReport> passes;  // a render in passes (scene.passes.enabled())
};

// What the caller of renderFrame controls while it runs. Every field is optional.
struct FrameControl {
    // Resume from and checkpoint to a partial file: tile by tile (renderer.h), or in a render
    // in passes pass by pass (passes.h). A caller that watches the render sets their hooks:
    // tiles->tileFinished sees the film after each tile, passes->passFinished after each pass.
    TileCheckpoint* tiles = nullptr;
    PassCheckpoint* passes = nullptr;
    // The caller's stop (core/cancel.h): no tile starts once it is raised, and a render in
    // passes keeps the whole passes before it (stats.interrupted says so). Null: SIGINT and
    // SIGTERM stop the render, as for the command line (core/interrupt.h).
    const CancelToken* cancel = nullptr;
};

// The photon integrator's settings for `scene`: its [render] photon keys, the render's seed and
// progress mode, and its [refraction] field (the photon pass of `render` and `mirage photons`).
PhotonIntegratorSettings photonSettingsFor(const Scene& scene);

// Renders `scene` with its integrator (scene.integrator, resolved by the loader) and develops it
// through `color`: one render of film.spp samples, or, when scene.passes asks, a render in
// passes (render/passes.h).
RenderedFrame renderFrame(const Scene& scene, const ColorPipeline& color,
                          const FrameControl& control = {});

}  // namespace mirage
