// A render in passes: see passes.h for the stopping rules and why they keep the render exact.
#include "render/passes.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <optional>

#include "core/cancel.h"
#include "core/clock.h"
#include "core/error.h"
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

// One render in passes, step by step (renderPasses, below): the film so far, the coarse image,
// and the sums of the passes' statistics.
class PassRender {
public:
    PassRender(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
               const PassSettings& settings, const PassRun& run)
        : mScene(scene),
          mIntegrator(integrator),
          mS(s),
          mSettings(settings),
          mRun(run),
          mResumed(run.checkpoint && run.checkpoint->initial),
          mBefore(mResumed ? run.checkpoint->secondsDone : 0.0),
          mState(mResumed ? *run.checkpoint->initial
                          : Film(renderWindow(s).width(), renderWindow(s).height(),
                                 aovLayout(scene, s))),
          mPassSettings(s) {
        mPassSettings.spp = settings.sppPerPass;
        mPassSettings.progress = Progress::Mode::Quiet;  // one line per pass instead
        if (!mResumed) return;
        mState.passes = run.checkpoint->passesDone;
        assess(settings, &mState);
    }

    // The coarse image, where the render begins with it: why the render stops there, or "" when
    // full passes follow.
    std::string startCoarse() {
        const CoarseStage& coarse = mRun.coarse;
        if (!coarse.integrator || mResumed || !coarseImagePossible(mS) ||
            (mSettings.coarseSpp <= 0 && mSettings.timeLimit <= 0))
            return "";
        CoarseImage& image = mCoarse.emplace(mS);
        image.cancel = mRun.cancel;
        if (mSettings.coarseSpp > 0)
            return addCoarse(mSettings.coarseSpp, &image) ? "coarse image (--coarse)"
                                                          : "interrupted";
        const auto t0 = Clock::now();
        if (!addCoarse(1, &image)) return "interrupted";
        const double perSample = secondsSince(t0);
        for (;;) {
            const double left = mSettings.timeLimit - elapsed();
            if (kPassInCoarseSamples * perSample <= left) return "";
            if (image.spp * perSample > left) return "time limit (coarse image: no full pass fits)";
            if (!addCoarse(image.spp, &image)) return "interrupted";
        }
    }

    // The next full pass: why the render stops before it or during it (a pass cut short is
    // dropped: the film keeps whole passes), or "" once it is in the film.
    // From here the passes' wall time counts (mirage:render_seconds).
    void startPasses() { mPassesStart = Clock::now(); }

    std::string nextPass() {
        const std::string stop = stopBefore(mSettings, mState, elapsed(), mLastPass);
        if (!stop.empty()) return stop;
        if (stopRequested(mRun.cancel)) return "interrupted";
        const auto t0 = Clock::now();
        mIntegrator.beginPass(mScene, mState.passes);
        TileCheckpoint from = passControl();
        const PassSamples samples{mState.passes * mSettings.sppPerPass,
                                  mState.pixels.empty() ? nullptr : &mState.pixels};
        RenderStats pass;
        Film next = render(mScene, mIntegrator, mPassSettings, &pass, &from, samples);
        if (pass.interrupted) return whyCut(from);
        addPass(std::move(next), pass, secondsSince(t0));
        return "";
    }

    PassResult finish(const std::string& stop) {
        const bool coarseIsTheImage = mCoarse && mState.passes == 0 && stop != "interrupted";
        if (coarseIsTheImage) mState.film = magnifyCoarse(*mCoarse, mS);
        RenderStats& sum = mSum;
        sum.tiles = tileCount(mS);
        sum.seconds = secondsSince(mPassesStart);  // the later passes' photon maps included
        sum.nonFiniteSamples = mState.film.nonFiniteSamples();
        sum.interrupted = stop == "interrupted";
        sum.tilesDone = sum.interrupted ? 0 : sum.tiles;
        PassReport report;
        report.passes = mState.passes;
        for (int y = 0; y < mState.film.height(); ++y)
            for (int x = 0; x < mState.film.width(); ++x)
                report.samples += mState.film.pixel(x, y).samples;
        report.estimatedError = mState.error.relError();
        report.seconds = elapsed();
        report.lastPassPixels = mLastPixels;
        report.stop = stop;
        if (coarseIsTheImage) reportCoarse(*mCoarse, *mRun.coarse.integrator, &report);
        return {std::move(mState.film), sum, report};
    }

private:
    // Seconds since the frame began, the runs before a resume included.
    double elapsed() const { return mBefore + secondsSince(mRun.frameStart); }

    // Adds `spp` samples to the coarse image and shows it, magnified, to the checkpoint's hook;
    // false when a stop came.
    bool addCoarse(int spp, CoarseImage* image) {
        if (!addCoarseSamples(mScene, *mRun.coarse.integrator, mS, spp, image)) return false;
        PassCheckpoint* c = mRun.checkpoint;
        if (c && c->coarseFinished) c->coarseFinished(magnifyCoarse(*image, mS), image->spp);
        return true;
    }

    // A pass ends at the time limit (no tile starts after it) where there is an image to fall
    // back on: the passes before it, or the coarse image.
    TileCheckpoint passControl() const {
        TileCheckpoint from;
        from.initial = &mState.film;
        from.cancel = mRun.cancel;
        if (mSettings.timeLimit > 0 && (mState.passes > 0 || mCoarse))
            from.deadline =
                mRun.frameStart + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                      std::chrono::duration<double>(mSettings.timeLimit - mBefore));
        return from;
    }

    // Why a pass was cut short: a stop, or the time limit's deadline.
    std::string whyCut(const TileCheckpoint& from) const {
        if (stopRequested(mRun.cancel) || from.deadline == Clock::time_point::max())
            return "interrupted";
        return mState.passes == 0 ? "time limit (coarse image: the first full pass did not fit)"
                                  : "time limit";
    }

    // A finished pass into the film: its statistics, the error estimate and the next mask, its
    // line, and the checkpoint's hooks.
    void addPass(Film next, const RenderStats& pass, double seconds) {
        addPassStats(pass, &mSum);
        mState.film = std::move(next);
        ++mState.passes;
        ++mPassesNow;
        mLastPass = seconds;
        const PixelWindow win = renderWindow(mS);
        mLastPixels =
            mState.pixels.empty()
                ? size_t(win.width()) * size_t(win.height())
                : size_t(std::count(mState.pixels.begin(), mState.pixels.end(), uint8_t(1)));
        assess(mSettings, &mState);
        if (mS.progress != Progress::Mode::Quiet)
            std::fprintf(stderr, "pass %d: %zu pixels, %.2fs, estimated error %.4g\n",
                         mState.passes, mLastPixels, mLastPass, mState.error.relError());
        PassCheckpoint* c = mRun.checkpoint;
        if (c && c->passFinished) c->passFinished(mState.film, mState.passes, elapsed());
        if (c && c->stopAfterPasses >= 0 && mPassesNow >= c->stopAfterPasses)
            requestInterrupt(SIGINT);
    }

    const RenderScene& mScene;
    Integrator& mIntegrator;
    const RenderSettings& mS;
    const PassSettings& mSettings;
    const PassRun& mRun;
    const bool mResumed;
    const double mBefore;  // seconds of the runs before a resume
    PassState mState;
    RenderSettings mPassSettings;  // one pass: pass_spp samples, quiet
    std::optional<CoarseImage> mCoarse;
    RenderStats mSum;
    Clock::time_point mPassesStart;
    double mLastPass = 0;
    size_t mLastPixels = 0;
    int mPassesNow = 0;
};

}  // namespace

int PassSettings::passCap() const {
    const int bySamples = kMaxSamplesPerPixel / std::max(sppPerPass, 1);
    return maxPasses > 0 ? std::min(maxPasses, bySamples) : bySamples;
}

PassResult renderPasses(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
                        const PassSettings& settings, const PassRun& run) {
    MIRAGE_CHECK(settings.sppPerPass >= 1);
    // A region's passes (--region with --passes) fill the region's film; an adaptive mask is
    // indexed by whole-frame pixel, so a noise threshold needs the whole frame (the command
    // refuses the pair).
    const PixelWindow win = renderWindow(s);
    MIRAGE_CHECK(settings.noiseThreshold <= 0 ||
                 (win.width() == s.width && win.height() == s.height));
    MIRAGE_CHECK(settings.coarseSpp <= 0 || (run.coarse.integrator && coarseImagePossible(s)));
    PassRender r(scene, integrator, s, settings, run);
    std::string stop = r.startCoarse();
    if (stop.empty() && run.coarse.prepareFullPasses) run.coarse.prepareFullPasses();
    r.startPasses();
    while (stop.empty()) stop = r.nextPass();
    return r.finish(stop);
}

}  // namespace mirage
