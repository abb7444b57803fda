// The render pass: tiles over the image, scheduled by TBB over all cores. Each pixel's samples
// use the counter-based sampler keyed by (seed, pixel, sample), and each pixel is accumulated
// by the one task that owns its tile, so the image is bit-identical for any thread count.
#pragma once

#include <cstdint>

#include "core/progress.h"
#include "film/film.h"
#include "render/integrator.h"

namespace mirage {

struct RenderSettings {
    int width = 640, height = 360;
    int tileSize = 32;
    int spp = 16;
    uint64_t seed = 0;
    Progress::Mode progress = Progress::Mode::Auto;
};

struct RenderStats {
    double seconds = 0;
    uint64_t samples = 0;
    uint64_t mediumLookups = 0;  // medium evaluations (each reads every grid of its shader)
    uint64_t nonFiniteSamples = 0;  // camera samples dropped by the film (NaN/∞)
    uint64_t cappedFlights = 0;     // free flights cut at the collision cap (tracking.h)
};

Film render(const RenderScene& scene, Integrator& integrator, const RenderSettings& settings,
            RenderStats* stats);

}  // namespace mirage
