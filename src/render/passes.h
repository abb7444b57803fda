// A render in passes: `--passes N`, `--time-limit SECONDS`, `--noise-threshold E` (docs/cli.md,
// "Renders in passes"). Each pass adds [render] pass_spp samples to every pixel that still
// needs them, continuing each pixel's sample indices (pass p takes samples [p·K, (p+1)·K) of
// the counter-based sampler), and the render stops only between passes, so the image is always
// the average of whole passes: never half-filled.
//
// Stopping, checked before each pass after the first: the pass cap; the estimated relative
// error of the image (film/film_error.h) at or below the noise threshold; the time limit, when
// the time spent (the frame's set-up and photon passes included) plus the last pass's duration
// would exceed it. A pass after the first that is still running at the time limit (the last
// pass's duration is a guess: the progressive photon mapper's later maps are larger than its
// first) starts no tile after it and is dropped. With a noise threshold, from pass
// kMinAdaptivePasses on, a pass samples only the pixels whose estimated error (the worst of their
// 3×3 neighbourhood) is above it.
//
// A time limit shorter than one full pass: with a time limit, the render first takes one sample
// of the coarse image (render/coarse_image.h), whose time predicts a full pass's
// (kPassInCoarseSamples of them). Where that does not fit in the time left, the coarse image
// doubles its samples while the next doubling fits, and is the image; where it fits, full passes
// follow, the first of them cut at the time limit (no tile starts after it), and a first pass so
// cut leaves the coarse image as the image. Once a full pass is finished the coarse image is
// dropped: the image is whole passes only, as without it.
//
// Determinism: which pixels a pass samples depends only on the film after the passes before,
// and an integrator's pass state only on the pass index (Integrator::beginPass), so N passes
// give the same bits for any thread count, and re-rendering with `--passes N`, N the count a
// time-limited render reached, reproduces it bit for bit. Without a noise threshold (every pixel
// in every pass) and with an integrator without pass state, N passes of K samples are the same
// bits as one render of N·K samples per pixel.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/clock.h"
#include "film/film.h"
#include "render/renderer.h"

namespace mirage {

class CancelToken;

// A pixel's samples are counted in 32 bits and capped with the --spp range.
constexpr int kMaxSamplesPerPixel = 1 << 20;
// Passes every pixel takes before adaptive sampling trusts its variance estimate.
constexpr int kMinAdaptivePasses = 2;

struct PassSettings {
    int maxPasses = 0;          // --passes; 0: no cap but kMaxSamplesPerPixel
    int sppPerPass = 4;         // [render] pass_spp
    double timeLimit = 0;       // --time-limit, seconds since the frame began; 0: none
    double noiseThreshold = 0;  // --noise-threshold, relative error (film_error.h); 0: none
    int coarseSpp = 0;          // --coarse: the coarse image alone, of this many samples; 0: none
    // A render in passes at all: otherwise the frame is one render of film.spp samples.
    bool enabled() const {
        return maxPasses > 0 || timeLimit > 0 || noiseThreshold > 0 || coarseSpp > 0;
    }
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
    // After each step of the coarse image (below: a time limit's first image): the coarse film
    // magnified to the frame, and its samples per pixel. A program shows it while passes follow.
    std::function<void(const Film&, int spp)> coarseFinished;
    int64_t stopAfterPasses = -1;  // test hook: raise the interrupt flag after this many passes
};

// A full pass costs about this many samples of the coarse image: 4× its pixels, and on the race
// scene one pass of the default photon mapper took as long as 13 coarse samples of the path
// tracer, one pass of the path tracer's 4 samples as long as 16.
constexpr double kPassInCoarseSamples = 16;

struct PassReport {
    int passes = 0;             // whole passes in the image (resumed ones included)
    int coarseSpp = 0;          // the image is the coarse image of this many samples; 0: passes
    std::string coarseIntegrator;  // what rendered the coarse image (coarseSpp > 0)
    uint64_t samples = 0;       // camera samples in the image
    double estimatedError = 0;  // √ of the estimated relMSE (film_error.h)
    double seconds = 0;         // since the frame began, all runs
    size_t lastPassPixels = 0;  // pixels the last pass sampled
    std::string stop;           // why it stopped: passes, time limit, noise threshold, interrupted
};

// The coarse image of a render in passes (above, and render/coarse_image.h).
struct CoarseStage {
    Integrator* integrator = nullptr;  // renders it; null: no coarse image
    // The frame integrator's set-up (its preprocess), left until a full pass needs it when the
    // coarse image does not (a photon mapper's first map); null: done before.
    std::function<void()> prepareFullPasses;
};

// How a render in passes runs beyond its settings. Every field is optional.
struct PassRun {
    Clock::time_point frameStart = Clock::now();  // when the frame began: its time limit counts
    PassCheckpoint* checkpoint = nullptr;         // resume from, and checkpoint, whole passes
    CoarseStage coarse;                           // its coarse image; none by default
    // The caller's stop (core/cancel.h), checked before each pass and between its tiles: a
    // pass cut short is dropped, the film keeps the whole passes before it. Null: SIGINT/SIGTERM.
    const CancelToken* cancel = nullptr;
};

// A render in passes: the film of its whole passes (or its coarse image, magnified), the sums of
// the passes' render statistics, its seconds the wall time of all passes, photon maps of passes
// after the first included (stats.interrupted: a stop came; the film holds the passes finished
// before), and how far it went and why it stopped.
struct PassResult {
    Film film;
    RenderStats stats;
    PassReport report;
};

// Renders passes of `passes.sppPerPass` samples until a stop (above). `run.coarse.integrator`
// renders the coarse image (null: none; then a time limit never cuts a pass); it is used only
// when coarseImagePossible(settings) and the render does not resume.
PassResult renderPasses(const RenderScene& scene, Integrator& integrator,
                        const RenderSettings& settings, const PassSettings& passes,
                        const PassRun& run = {});

}  // namespace mirage
