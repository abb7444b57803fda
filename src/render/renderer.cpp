#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <atomic>
#include <csignal>
#include <memory>
#include <mutex>
#include <optional>

#include "core/cancel.h"
#include "core/error.h"
#include "render/achromatic_film.h"
#include "render/camera_ray_data.h"

namespace mirage {

namespace {

// What every tile of one render reads, and the film (and deep film) the tiles fill.
struct TileJob {
    const RenderScene& scene;
    const Integrator& integrator;
    const RenderSettings& s;
    const PassSamples& pass;
    PixelWindow win;  // the render window (renderWindow)
    PerspectiveCamera camera;
    // Colour exactly per sample where nothing in the scene is spectral (render(), below).
    std::optional<AchromaticFilm> achromatic;
    bool walkCameraRay;  // the data passes or deep output record the camera ray
    uint64_t dataSeed;   // the camera ray data's numbers
    Film* film;
    DeepFilm* deep;
};

// A tile's records of the sample being rendered (its passes, its deep record) and of the pixel
// being rendered (its deep samples), reused from sample to sample.
struct TileScratch {
    explicit TileScratch(const AovLayout& layout) : aov(layout) {}
    AovSample aov;
    DeepSample deep;
    DeepPixel deepPixel;
};

// Tile `tile`'s pixels in the full frame: tiles are numbered as renderer.h says, the last ones
// of a row or column clipped to the render window.
PixelWindow tilePixels(const RenderSettings& s, int tile) {
    const PixelWindow win = renderWindow(s);
    const int tilesX = tileCountX(s);
    const int x0 = win.x0 + (tile % tilesX) * s.tileSize;
    const int y0 = win.y0 + (tile / tilesX) * s.tileSize;
    return {x0, y0, std::min(x0 + s.tileSize, win.x1), std::min(y0 + s.tileSize, win.y1)};
}

// Sample i of pixel (x, y) into the film. Its numbers come from its own (seed, pixel, sample),
// the pixel numbered in the full frame whatever the region and the tile: pixel jitter, its
// wavelengths, then the integrator's; its time in the shutter from a stream of its own, so
// that a closed shutter leaves every other number where it was. A camera that moves within the
// shutter is placed at that time (CameraDesc::poseAt) for the sample's ray. With AOVs, ts.aov
// collects the sample's passes, and the camera ray's data passes take numbers of their own too.
void renderSample(const TileJob& job, int x, int y, int i, ThreadState& ts, TileScratch& scratch) {
    const RenderScene& scene = job.scene;
    const RenderSettings& s = job.s;
    const uint64_t pixel = uint64_t(y) * uint64_t(s.width) + uint64_t(x);
    Sampler sampler(s.sampler, s.seed, pixel, uint64_t(i));
    const float jx = sampler.get1D(), jy = sampler.get1D();
    const SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
    ts.tracking.setWavelengths(w);
    float time = 0.f;
    if (scene.camera.motionBlur()) {
        time = shutterTime(scene.camera, s.seed, pixel, uint64_t(i));
        ts.tracking.setTimeOffset(time);
    }
    const Ray ray = scene.camera.moves()
                        ? PerspectiveCamera(scene.camera.poseAt(time), s.width, s.height)
                              .generate(float(x) + jx, float(y) + jy)
                        : job.camera.generate(float(x) + jx, float(y) + jy);
    if (ts.aov) scratch.aov.reset();
    if (ts.deep) scratch.deep.reset();
    std::optional<Sampler> data;
    std::optional<CameraRayData> record;
    if (job.walkCameraRay) {
        data.emplace(SamplerKind::Random, job.dataSeed, pixel, uint64_t(i));
        ts.cameraData = &record.emplace(scene, ray, w, *data, ts, ts.aov, ts.deep);
    }
    RadianceSample rs = job.integrator.Li(scene, ray, w, sampler, ts);
    if (job.achromatic) job.achromatic->apply(w, &rs);
    if (record) {
        record->finish();
        ts.cameraData = nullptr;
        if (job.film->aovs().coverage()) scratch.aov.scaleCoverage(rs.alpha);
    }
    const bool kept =
        job.film->addSample(x - job.win.x0, y - job.win.y0, rs.L, w, rs.alpha, rs.xyz, ts.aov);
    if (ts.deep && kept) scratch.deepPixel.addSample(scratch.deep, w, rs.alpha);
}

// Every sample of one tile's pixels into the film (tiles do not overlap: no two threads write
// one pixel), and each pixel's deep samples merged once it has all of them. Returns the samples
// taken.
uint64_t renderTile(const TileJob& job, int tile, ThreadState& ts) {
    const RenderSettings& s = job.s;
    const AovLayout& layout = job.film->aovs();
    TileScratch scratch(layout);
    ts.aov = layout.empty() ? nullptr : &scratch.aov;
    ts.exactEmission = job.achromatic && job.achromatic->exactEmission();
    ts.lightSplit.assign(size_t(layout.groupSlots()), SampledSpectrum(0.f));
    ts.deep = job.deep ? &scratch.deep : nullptr;
    const PixelWindow t = tilePixels(s, tile);
    uint64_t taken = 0;
    for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) {
            const uint64_t pixel = uint64_t(y) * uint64_t(s.width) + uint64_t(x);
            if (job.pass.pixels && !(*job.pass.pixels)[pixel]) continue;
            taken += uint64_t(s.spp);
            for (int i = job.pass.first; i < job.pass.first + s.spp; ++i)
                renderSample(job, x, y, i, ts, scratch);
            if (!job.deep) continue;
            const uint32_t samples = job.film->pixel(x - job.win.x0, y - job.win.y0).samples;
            job.deep->setPixel(x, y, scratch.deepPixel.merge(s.deep, samples));
            scratch.deepPixel.clear();
        }
    ts.aov = nullptr;
    ts.deep = nullptr;
    return taken;
}

// The tile scheduler's board: which tiles are finished, whether the next may start, and what a
// finished tile sets off (progress, the checkpoint hook, the test hook). A tile's pixels are
// written before its flag is stored (release) and read by a checkpoint writer only after it
// loads the flag (acquire): no data race.
class TileBoard {
public:
    TileBoard(const RenderSettings& s, TileCheckpoint* checkpoint)
        : mCheckpoint(checkpoint),
          mTiles(tileCount(s)),
          mDone(new std::atomic<uint8_t>[size_t(mTiles)]) {
        for (int t = 0; t < mTiles; ++t) {
            const bool d = checkpoint && size_t(t) < checkpoint->done.size() && checkpoint->done[t];
            mDone[t].store(d ? 1 : 0, std::memory_order_relaxed);
            mResumed += d;
        }
        mProgress.emplace("render", uint64_t(mTiles), "tiles", s.progress);
        if (mResumed > 0) mProgress->advance(uint64_t(mResumed));
    }

    int tiles() const { return mTiles; }
    int resumed() const { return mResumed; }
    Progress& progress() { return *mProgress; }

    // Whether `tile` is to be rendered: not finished, and neither a stop (a cancel, a signal)
    // nor the deadline has come.
    bool pending(int tile) const {
        const TileCheckpoint* c = mCheckpoint;
        return !mDone[tile].load(std::memory_order_relaxed) &&
               !stopRequested(c ? c->cancel : nullptr) &&
               !(c && std::chrono::steady_clock::now() >= c->deadline);
    }

    // After `tile` was rendered into `film`. A thread that finds the checkpoint writer busy goes
    // on rendering instead of waiting.
    void finish(int tile, const Film& film) {
        mDone[tile].store(1, std::memory_order_release);
        mProgress->advance();
        const int64_t n = ++mFinishedNow;
        TileCheckpoint* c = mCheckpoint;
        if (!c) return;
        if (c->stopAfterTiles >= 0 && n >= c->stopAfterTiles) requestInterrupt(SIGINT);
        if (c->tileFinished && mCheckpointMutex.try_lock()) {
            std::lock_guard<std::mutex> lock(mCheckpointMutex, std::adopt_lock);
            c->tileFinished(film, snapshot());
        }
    }

    std::vector<uint8_t> snapshot() const {
        std::vector<uint8_t> v(size_t(mTiles), 0);
        for (int t = 0; t < mTiles; ++t) v[t] = mDone[t].load(std::memory_order_acquire);
        return v;
    }

private:
    TileCheckpoint* mCheckpoint;
    int mTiles;
    int mResumed = 0;
    std::unique_ptr<std::atomic<uint8_t>[]> mDone;
    std::optional<Progress> mProgress;
    std::atomic<int64_t> mFinishedNow{0};
    std::mutex mCheckpointMutex;
};

// The tracking counters of a render, summed over its threads.
struct TileCounters {
    std::atomic<uint64_t> samples{0}, lookups{0}, cappedFlights{0}, aboveMajorant{0};
};

// The pending tiles over all cores, one tile per task (simple_partitioner, grain 1), so that a
// stop ends the hand-out of tiles within one tile's time on every thread.
void renderTiles(const TileJob& job, TileBoard& board, TileCounters* counters) {
    tbb::enumerable_thread_specific<ThreadState> states([&] { return ThreadState(job.scene); });
    tbb::parallel_for(
        tbb::blocked_range<int>(0, board.tiles(), 1),
        [&](const tbb::blocked_range<int>& r) {
            ThreadState& ts = states.local();
            const uint64_t lookups = ts.tracking.lookups, capped = ts.tracking.cappedFlights;
            const uint64_t above = ts.tracking.aboveMajorant;
            for (int tile = r.begin(); tile < r.end(); ++tile) {
                if (!board.pending(tile)) continue;
                counters->samples += renderTile(job, tile, ts);
                board.finish(tile, *job.film);
            }
            counters->lookups += ts.tracking.lookups - lookups;
            counters->cappedFlights += ts.tracking.cappedFlights - capped;
            counters->aboveMajorant += ts.tracking.aboveMajorant - above;
        },
        tbb::simple_partitioner());
    board.progress().finish();
}

// The statistics of a render whose finished tiles are `done`.
RenderStats tileStats(const TileJob& job, TileBoard& board, const std::vector<uint8_t>& done,
                      const TileCounters& counters) {
    RenderStats stats;
    uint64_t pixelsDone = 0;
    for (int t = 0; t < board.tiles(); ++t) {
        if (!done[t]) continue;
        ++stats.tilesDone;
        const PixelWindow w = tilePixels(job.s, t);
        pixelsDone += uint64_t(w.width()) * uint64_t(w.height());
    }
    stats.seconds = board.progress().elapsedSeconds();
    // With a pixel mask, the samples this pass took; else those the finished tiles hold.
    stats.samples = job.pass.pixels ? counters.samples.load() : pixelsDone * uint64_t(job.s.spp);
    stats.mediumLookups = counters.lookups.load();
    stats.nonFiniteSamples = job.film->nonFiniteSamples();
    stats.tiles = board.tiles();
    stats.tilesResumed = board.resumed();
    stats.interrupted = stats.tilesDone < stats.tiles;
    stats.cappedFlights = counters.cappedFlights.load();
    stats.aboveMajorant = counters.aboveMajorant.load();
    return stats;
}

}  // namespace

AovLayout aovLayout(const RenderScene& scene, const RenderSettings& s) {
    return AovLayout(s.aovs, scene.lightGroupNames(), scene.cryptoObjects);
}

Film render(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
            RenderStats* stats, TileCheckpoint* checkpoint, const PassSamples& pass,
            DeepFilm* deep) {
    const PixelWindow win = renderWindow(s);
    MIRAGE_CHECK(win.x0 >= 0 && win.y0 >= 0 && win.x1 <= s.width && win.y1 <= s.height);
    Film film = checkpoint && checkpoint->initial
                    ? *checkpoint->initial
                    : Film(win.width(), win.height(), aovLayout(scene, s));
    MIRAGE_CHECK(film.width() == win.width() && film.height() == win.height());
    MIRAGE_CHECK(film.aovs().stride() == aovLayout(scene, s).stride());
    MIRAGE_CHECK(!pass.pixels || pass.pixels->size() == size_t(s.width) * size_t(s.height));
    // Deep pixels are numbered in the whole frame; the command refuses deep with a region.
    MIRAGE_CHECK(!deep || (win.width() == s.width && win.height() == s.height));
    // Colour exactly per sample where nothing in the scene is spectral; not with passes that
    // split each sample's spectral radiance (light paths, light groups) or deep samples, which
    // must sum to the beauty exactly. Data passes describe the camera ray, not its light: the
    // beauty keeps its exact colour (and its bits) with them.
    const TileJob job{scene,
                      integrator,
                      s,
                      pass,
                      win,
                      PerspectiveCamera(scene.camera, s.width, s.height),
                      !film.aovs().splitsRadiance() && !deep
                          ? AchromaticFilm::forScene(scene, integrator)
                          : std::nullopt,
                      film.aovs().cameraData() || deep,
                      hashCombine(s.seed, 0x616f7664617461ull),  // "aovdata"
                      &film,
                      deep};

    TileBoard board(s, checkpoint);
    TileCounters counters;
    renderTiles(job, board, &counters);
    const std::vector<uint8_t> done = board.snapshot();
    if (checkpoint) checkpoint->done = done;
    if (stats) *stats = tileStats(job, board, done, counters);
    return film;
}

}  // namespace mirage
