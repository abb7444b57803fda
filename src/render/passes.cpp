// A render in passes: see passes.h for the stopping rules and why they keep the render exact.
#include "render/passes.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <optional>

#include "core/clock.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "film/film_error.h"
#include "render/coarse_image.h"

namespace mirage {

namespace {

// One pass's render statistics into the running sums.
void addPassStats(const RenderStats& pass, RenderStats* sum) {
    sum->samples += pass.samples;
    sum->mediumLookups += pass.mediumLookups;
    sum->cappedFlights += pass.cappedFlights;
    sum->aboveMajorant += pass.aboveMajorant;
    sum->tiles = pass.tiles;
}

// The state between passes: the film so far, its estimated error and which pixels the next
// pass samples.
struct PassState {
    explicit PassState(Film f) : film(std::move(f)) {}
    Film film;
    int passes = 0;
    FilmError error;
    std::vector<uint8_t> pixels;  // empty: every pixel
};

// After `state.passes` passes: the error estimate and, with a noise threshold, the next mask.
void assess(const PassSettings& settings, PassState* state) {
    state->error = estimateFilmError(state->film);
    if (settings.noiseThreshold > 0 && state->passes >= kMinAdaptivePasses)
        state->pixels = noisyPixels(state->film, state->error, settings.noiseThreshold);
}

// Why the render stops before the next pass, or "" to go on.
std::string stopBefore(const PassSettings& settings, const PassState& state, double elapsed,
                       double lastPass) {
    if (state.passes >= settings.passCap()) return "passes";
    if (state.passes == 0) return "";
    if (settings.noiseThreshold > 0) {
        if (state.error.relError() <= settings.noiseThreshold) return "noise threshold";
        if (!state.pixels.empty() &&
            std::none_of(state.pixels.begin(), state.pixels.end(), [](uint8_t a) { return a; }))
            return "noise threshold (every pixel)";
    }
    if (settings.timeLimit > 0 && elapsed + lastPass > settings.timeLimit) return "time limit";
    return "";
}

// The coarse image's part of a render (passes.h): renders it into `image`, and says why the
// render stops there, or "" when full passes follow.
std::string startCoarse(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
                        const PassSettings& settings, double before,
                        std::chrono::steady_clock::time_point frameStart,
                        std::optional<CoarseImage>* image) {
    CoarseImage& coarse = image->emplace(s);
    if (settings.coarseSpp > 0)
        return addCoarseSamples(scene, integrator, s, settings.coarseSpp, &coarse)
                   ? "coarse image (--coarse)"
                   : "interrupted";
    const auto t0 = std::chrono::steady_clock::now();
    if (!addCoarseSamples(scene, integrator, s, 1, &coarse)) return "interrupted";
    const double perSample = secondsSince(t0);
    for (;;) {
        const double left = settings.timeLimit - (before + secondsSince(frameStart));
        if (kPassInCoarseSamples * perSample <= left) return "";
        if (coarse.spp * perSample > left) return "time limit (coarse image: no full pass fits)";
        if (!addCoarseSamples(scene, integrator, s, coarse.spp, &coarse)) return "interrupted";
    }
}

// The report of a render whose image is its coarse image.
void reportCoarse(const CoarseImage& coarse, const Integrator& integrator, PassReport* report) {
    report->passes = 0;
    report->coarseSpp = coarse.spp;
    report->coarseIntegrator = integrator.name();
    report->samples =
        uint64_t(coarse.film.width()) * uint64_t(coarse.film.height()) * uint64_t(coarse.spp);
    report->estimatedError = estimateFilmError(coarse.film).relError();
    report->lastPassPixels = size_t(coarse.film.width()) * size_t(coarse.film.height());
}

}  // namespace

int PassSettings::passCap() const {
    const int bySamples = kMaxSamplesPerPixel / std::max(sppPerPass, 1);
    return maxPasses > 0 ? std::min(maxPasses, bySamples) : bySamples;
}

Film renderPasses(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
                  const PassSettings& settings, std::chrono::steady_clock::time_point frameStart,
                  RenderStats* stats, PassReport* report, PassCheckpoint* checkpoint,
                  const CoarseStage& coarse) {
    MIRAGE_CHECK(settings.sppPerPass >= 1);
    const bool resumed = checkpoint && checkpoint->initial;
    // A region's passes (--region with --passes) fill the region's film; an adaptive mask is
    // indexed by whole-frame pixel, so a noise threshold needs the whole frame (the command
    // refuses the pair).
    const PixelWindow win = renderWindow(s);
    MIRAGE_CHECK(settings.noiseThreshold <= 0 ||
                 (win.width() == s.width && win.height() == s.height));
    MIRAGE_CHECK(settings.coarseSpp <= 0 || (coarse.integrator && coarseImagePossible(s)));
    PassState state(resumed ? *checkpoint->initial
                            : Film(win.width(), win.height(), aovLayout(scene, s)));
    const double before = resumed ? checkpoint->secondsDone : 0.0;
    if (resumed) {
        state.passes = checkpoint->passesDone;
        assess(settings, &state);
    }
    std::optional<CoarseImage> coarseImage;
    std::string stop;
    if (coarse.integrator && !resumed && coarseImagePossible(s) &&
        (settings.coarseSpp > 0 || settings.timeLimit > 0))
        stop =
            startCoarse(scene, *coarse.integrator, s, settings, before, frameStart, &coarseImage);
    if (stop.empty() && coarse.prepareFullPasses) coarse.prepareFullPasses();
    RenderSettings passSettings = s;
    passSettings.spp = settings.sppPerPass;
    passSettings.progress = Progress::Mode::Quiet;  // one line per pass instead
    RenderStats sum;
    sum.tiles = tileCount(s);
    const auto passesStart = std::chrono::steady_clock::now();
    double lastPass = 0;
    size_t lastPixels = 0;
    int passesNow = 0;
    while (stop.empty()) {
        stop = stopBefore(settings, state, before + secondsSince(frameStart), lastPass);
        if (!stop.empty()) break;
        if (interruptRequested()) {
            stop = "interrupted";
            break;
        }
        const auto t0 = std::chrono::steady_clock::now();
        integrator.beginPass(scene, state.passes);
        TileCheckpoint from;
        from.initial = &state.film;
        // A pass ends at the time limit (no tile starts after it) where there is an image to
        // fall back on: the passes before it, or the coarse image.
        const bool cutAtLimit = settings.timeLimit > 0 && (state.passes > 0 || coarseImage);
        if (cutAtLimit)
            from.deadline =
                frameStart + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                 std::chrono::duration<double>(settings.timeLimit - before));
        const PassSamples samples{state.passes * settings.sppPerPass,
                                  state.pixels.empty() ? nullptr : &state.pixels};
        RenderStats pass;
        Film next = render(scene, integrator, passSettings, &pass, &from, samples);
        if (pass.interrupted) {  // a pass cut short is dropped: the film keeps whole passes
            if (interruptRequested() || !cutAtLimit)
                stop = "interrupted";
            else
                stop = state.passes == 0
                           ? "time limit (coarse image: the first full pass did not fit)"
                           : "time limit";
            break;
        }
        addPassStats(pass, &sum);
        state.film = std::move(next);
        ++state.passes;
        ++passesNow;
        lastPass = secondsSince(t0);
        lastPixels = state.pixels.empty()
                         ? size_t(win.width()) * size_t(win.height())
                         : size_t(std::count(state.pixels.begin(), state.pixels.end(), uint8_t(1)));
        assess(settings, &state);
        if (s.progress != Progress::Mode::Quiet)
            std::fprintf(stderr, "pass %d: %zu pixels, %.2fs, estimated error %.4g\n", state.passes,
                         lastPixels, lastPass, state.error.relError());
        if (checkpoint && checkpoint->passFinished)
            checkpoint->passFinished(state.film, state.passes, before + secondsSince(frameStart));
        if (checkpoint && checkpoint->stopAfterPasses >= 0 &&
            passesNow >= checkpoint->stopAfterPasses)
            requestInterrupt(SIGINT);
    }
    const bool coarseIsTheImage = coarseImage && state.passes == 0 && stop != "interrupted";
    if (coarseIsTheImage) state.film = magnifyCoarse(*coarseImage, s);
    sum.seconds = secondsSince(passesStart);  // the later passes' photon maps included
    sum.nonFiniteSamples = state.film.nonFiniteSamples();
    sum.interrupted = stop == "interrupted";
    sum.tilesDone = sum.interrupted ? 0 : sum.tiles;
    if (stats) *stats = sum;
    if (report) {
        report->passes = state.passes;
        report->samples = 0;
        for (int y = 0; y < state.film.height(); ++y)
            for (int x = 0; x < state.film.width(); ++x)
                report->samples += state.film.pixel(x, y).samples;
        report->estimatedError = state.error.relError();
        report->seconds = before + secondsSince(frameStart);
        report->lastPassPixels = lastPixels;
        report->stop = stop;
        if (coarseIsTheImage) reportCoarse(*coarseImage, *coarse.integrator, report);
    }
    return std::move(state.film);
}

}  // namespace mirage
