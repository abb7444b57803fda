// The render pass: tiles over the image, scheduled by TBB over all cores. Each pixel's samples
// use the sampler keyed by (seed, pixel, sample), and each pixel is accumulated
// by the one task that owns its tile, so the image is bit-identical for any thread count — and
// for any order or subset of tiles, which is what lets a killed render resume exactly, and a
// region of the frame render the same bits as those pixels of the whole frame (a farm's tiles).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "film/deep.h"
#include "film/film.h"
#include "render/integrator.h"

namespace mirage {

class CancelToken;

// A rectangle of pixels [x0, x1) × [y0, y1) in the full frame; empty: the whole frame.
struct PixelWindow {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool operator==(const PixelWindow& o) const {
        return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1;
    }
};

struct RenderSettings {
    int width = 640, height = 360;  // the full frame: the camera's image plane
    // --region: only these pixels are rendered, into a film of the region's size whose pixel
    // (0, 0) is the region's corner; empty: the whole frame.
    PixelWindow region;
    int tileSize = 32;
    int spp = 16;
    uint64_t seed = 0;
    // The camera samples' numbers (core/rng.h): Sobol is stratified over each pixel's samples.
    SamplerKind sampler = SamplerKind::Sobol;
    Progress::Mode progress = Progress::Mode::Auto;
    // Render passes beside the beauty (film/aov.h; [output] aovs, --aov), in the order of
    // their layers. Empty: the beauty alone, at its old cost and bits.
    std::vector<std::string> aovs;
    // Deep output ([output] deep, --deep): a path is what turns it on; the tolerances merge a
    // pixel's events into deep samples (film/deep.h).
    DeepSettings deep;
};

// The passes `s` asks for, with the scene's light groups (every integrator fills every pass).
// Throws MirageError for an unknown or repeated pass.
AovLayout aovLayout(const RenderScene& scene, const RenderSettings& s);

struct RenderStats {
    double seconds = 0;
    uint64_t samples = 0;
    uint64_t mediumLookups = 0;     // medium evaluations (each reads every grid of its shader)
    uint64_t nonFiniteSamples = 0;  // camera samples dropped by the film (NaN/∞)
    uint64_t cappedFlights = 0;     // free flights cut at the collision cap (tracking.h)
    uint64_t aboveMajorant = 0;     // lookups whose σt exceeded their majorant (must be 0)
    int tiles = 0;                  // tiles in the image
    int tilesDone = 0;              // finished, including those restored from a partial file
    int tilesResumed = 0;           // restored from a partial file, not rendered now
    bool interrupted = false;       // stopped (a cancel, a signal, the deadline) before the end
};

// The pixels a render covers: the region, or the whole frame.
inline PixelWindow renderWindow(const RenderSettings& s) {
    return s.region.empty() ? PixelWindow{0, 0, s.width, s.height} : s.region;
}

// Tiles are numbered row-major over the render window: tile t covers x from
// x0 + (t % tilesX)·tileSize, y from y0 + (t / tilesX)·tileSize, clipped to the window.
inline int tileCountX(const RenderSettings& s) {
    return (renderWindow(s).width() + s.tileSize - 1) / s.tileSize;
}
inline int tileCount(const RenderSettings& s) {
    return tileCountX(s) * ((renderWindow(s).height() + s.tileSize - 1) / s.tileSize);
}

// How a render runs beyond its settings: resuming and checkpointing (killed renders,
// --resume), its deadline and its stop. All fields are optional.
struct TileCheckpoint {
    // Resume: the film restored from a partial file and which tiles it holds (1 = finished);
    // those tiles are not rendered again. Sizes must match the settings.
    const Film* initial = nullptr;
    std::vector<uint8_t> done;
    // Called after a tile finishes, by one thread at a time (others skip while it runs), with
    // the film and which tiles are finished; it must read only finished tiles' pixels, and
    // decides itself whether writing a checkpoint now is worth its cost.
    std::function<void(const Film&, const std::vector<uint8_t>& done)> tileFinished;
    // Test hook: raise the interrupt flag (as SIGINT) after this many tiles finish in this run.
    int64_t stopAfterTiles = -1;
    // No tile starts after this time (a time limit's end, render/passes.h); the tiles left are
    // undone, as after an interrupt. Default: none.
    std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
    // The caller's stop (core/cancel.h): no tile starts once it is raised. Null: SIGINT/SIGTERM.
    const CancelToken* cancel = nullptr;
};

// One pass of a render in passes (render/passes.h): the samples of each pixel it adds, and which
// pixels. The default is the whole render: samples [0, spp) of every pixel.
struct PassSamples {
    int first = 0;  // sample indices [first, first + settings.spp), summed in that order
    const std::vector<uint8_t>* pixels = nullptr;  // row-major, 1 = sample; null = every pixel
};

// Renders every tile not already done, stopping early when a stop is requested
// (checkpoint->cancel, else a signal: tiles in flight finish; the rest are left undone, and
// stats->interrupted is set). On return,
// checkpoint->done (if given) says which tiles the film holds.
// With `deep` (settings.deep.path set), every rendered pixel's deep samples go there.
Film render(const RenderScene& scene, Integrator& integrator, const RenderSettings& settings,
            RenderStats* stats, TileCheckpoint* checkpoint = nullptr, const PassSamples& pass = {},
            DeepFilm* deep = nullptr);

}  // namespace mirage
