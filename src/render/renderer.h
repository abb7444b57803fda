// The render pass: tiles over the image, scheduled by TBB over all cores. Each pixel's samples
// use the sampler keyed by (seed, pixel, sample), and each pixel is accumulated
// by the one task that owns its tile, so the image is bit-identical for any thread count — and
// for any order or subset of tiles, which is what lets a killed render resume exactly.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/progress.h"
#include "film/deep.h"
#include "film/film.h"
#include "render/integrator.h"

namespace mirage {

struct RenderSettings {
    int width = 640, height = 360;
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

// The passes `s` asks for, with the scene's light groups. Throws MirageError for an unknown
// pass, and for light groups with an integrator whose photons do not record their light.
AovLayout aovLayout(const RenderScene& scene, const RenderSettings& s, const IntegratorInfo& info);

struct RenderStats {
    double seconds = 0;
    uint64_t samples = 0;
    uint64_t mediumLookups = 0;  // medium evaluations (each reads every grid of its shader)
    uint64_t nonFiniteSamples = 0;  // camera samples dropped by the film (NaN/∞)
    uint64_t cappedFlights = 0;     // free flights cut at the collision cap (tracking.h)
    uint64_t aboveMajorant = 0;     // lookups whose σt exceeded their majorant (must be 0)
    int tiles = 0;             // tiles in the image
    int tilesDone = 0;         // finished, including those restored from a partial file
    int tilesResumed = 0;      // restored from a partial file, not rendered now
    bool interrupted = false;  // stopped by interruptRequested() before every tile was done
};

// Tiles are numbered row-major: tile t covers x from (t % tilesX)·tileSize, y from
// (t / tilesX)·tileSize, clipped to the image.
inline int tileCountX(const RenderSettings& s) { return (s.width + s.tileSize - 1) / s.tileSize; }
inline int tileCount(const RenderSettings& s) {
    return tileCountX(s) * ((s.height + s.tileSize - 1) / s.tileSize);
}

// Checkpointing a render (killed renders, --resume). All fields are optional.
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
};

// Renders every tile not already done, stopping early when interruptRequested() (tiles in
// flight finish; the rest are left undone, and stats->interrupted is set). On return,
// checkpoint->done (if given) says which tiles the film holds.
// With `deep` (settings.deep.path set), every rendered pixel's deep samples go there.
Film render(const RenderScene& scene, Integrator& integrator, const RenderSettings& settings,
            RenderStats* stats, TileCheckpoint* checkpoint = nullptr, DeepFilm* deep = nullptr);

}  // namespace mirage
