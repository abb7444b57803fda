// A render in passes: `--passes N`, `--time-limit SECONDS`, `--noise-threshold E` (docs/cli.md,
// "Renders in passes"). Each pass adds [render] pass_spp samples to every pixel that still
// needs them, continuing each pixel's sample indices (pass p takes samples [p·K, (p+1)·K) of
// the counter-based sampler), and the render stops only between passes, so the image is always
// the average of whole passes: never half-filled.
//
// Stopping, checked before each pass after the first: the pass cap; the estimated relative
// error of the image (film/film_error.h) at or below the noise threshold; the time limit, when
// the time spent (the frame's set-up and photon passes included) plus the last pass's duration
// would exceed it. With a noise threshold, from pass kMinAdaptivePasses on, a pass samples only
// the pixels whose estimated error (the worst of their 3×3 neighbourhood) is above it.
//
// Determinism: which pixels a pass samples depends only on the film after the passes before,
// and an integrator's pass state only on the pass index (Integrator::beginPass), so N passes
// give the same bits for any thread count, and re-rendering with `--passes N`, N the count a
// time-limited render reached, reproduces it bit for bit. Without a noise threshold (every pixel
// in every pass) and with an integrator without pass state, N passes of K samples are the same
// bits as one render of N·K samples per pixel.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "film/film.h"
#include "render/renderer.h"

namespace mirage {

// A pixel's samples are counted in 32 bits and capped with the --spp range.
constexpr int kMaxSamplesPerPixel = 1 << 20;
// Passes every pixel takes before adaptive sampling trusts its variance estimate.
constexpr int kMinAdaptivePasses = 2;

struct PassSettings {
    int maxPasses = 0;          // --passes; 0: no cap but kMaxSamplesPerPixel
    int sppPerPass = 4;         // [render] pass_spp
    double timeLimit = 0;       // --time-limit, seconds since the frame began; 0: none
    double noiseThreshold = 0;  // --noise-threshold, relative error (film_error.h); 0: none
    // A render in passes at all: otherwise the frame is one render of film.spp samples.
    bool enabled() const { return maxPasses > 0 || timeLimit > 0 || noiseThreshold > 0; }
    int passCap() const;
};

// Killed renders in passes: the film after whole passes goes to the partial file, and --resume
// continues from it with the next pass.
struct PassCheckpoint {
    const Film* initial = nullptr;  // resume: the film after passesDone passes
    int passesDone = 0;
    double secondsDone = 0;  // seconds of the runs before (they count towards the time limit)
    // After every pass: the film, the passes in it and the seconds spent on them (all runs).
    std::function<void(const Film&, int passes, double seconds)> passFinished;
    int64_t stopAfterPasses = -1;  // test hook: raise the interrupt flag after this many passes
};

struct PassReport {
    int passes = 0;             // whole passes in the image (resumed ones included)
    uint64_t samples = 0;       // camera samples in the image
    double estimatedError = 0;  // √ of the estimated relMSE (film_error.h)
    double seconds = 0;         // since the frame began, all runs
    size_t lastPassPixels = 0;  // pixels the last pass sampled
    std::string stop;           // why it stopped: passes, time limit, noise threshold, interrupted
};

// Renders passes of `passes.sppPerPass` samples until a stop (above); `frameStart` is when the
// frame began (its time limit counts from there). `stats` sums the passes' render statistics,
// its seconds the wall time of all passes, photon maps of passes after the first included
// (stats->interrupted: an interrupt stopped it; the film holds the passes finished before).
Film renderPasses(const RenderScene& scene, Integrator& integrator, const RenderSettings& settings,
                  const PassSettings& passes, std::chrono::steady_clock::time_point frameStart,
                  RenderStats* stats, PassReport* report, PassCheckpoint* checkpoint = nullptr);

}  // namespace mirage
