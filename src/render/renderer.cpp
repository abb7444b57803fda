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

#include "core/error.h"
#include "core/interrupt.h"
#include "render/achromatic_film.h"
#include "render/camera_ray_data.h"

namespace mirage {

namespace {

// Every sample of one tile's pixels into the film (tiles do not overlap: no two threads write
// one pixel). A sample's numbers come from its own (seed, pixel, sample), the pixel numbered in
// the full frame whatever the region and the tile: pixel jitter, its wavelengths, then the
// integrator's; its time in the shutter from a stream of its own, so that a closed shutter
// leaves every other number where it was. A camera that moves within the shutter is placed at
// that time (CameraDesc::poseAt) for the sample's ray. With AOVs, ts.aov collects each sample's
// passes, and the camera ray's data passes take numbers of their own too. Returns the samples
// taken.
uint64_t renderTile(const RenderScene& scene, const Integrator& integrator, const RenderSettings& s,
                    const PassSamples& pass, const PerspectiveCamera& camera,
                    const std::optional<AchromaticFilm>& achromatic, int tile, ThreadState& ts,
                    Film* film, DeepFilm* deepFilm) {
    const PixelWindow win = renderWindow(s);
    const AovLayout& layout = film->aovs();
    AovSample aov(layout);
    ts.aov = layout.empty() ? nullptr : &aov;
    ts.lightSplit.assign(size_t(layout.groupSlots()), SampledSpectrum(0.f));
    DeepSample deep;
    DeepPixel deepPixel;
    ts.deep = deepFilm ? &deep : nullptr;
    const bool walkCameraRay = layout.cameraData() || deepFilm;
    const uint64_t dataSeed = hashCombine(s.seed, 0x616f7664617461ull);  // "aovdata"
    const int tilesX = tileCountX(s);
    const int x0 = win.x0 + (tile % tilesX) * s.tileSize;
    const int y0 = win.y0 + (tile / tilesX) * s.tileSize;
    const int x1 = std::min(x0 + s.tileSize, win.x1), y1 = std::min(y0 + s.tileSize, win.y1);
    uint64_t taken = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const uint64_t pixel = uint64_t(y) * uint64_t(s.width) + uint64_t(x);
            if (pass.pixels && !(*pass.pixels)[pixel]) continue;
            taken += uint64_t(s.spp);
            for (int i = pass.first; i < pass.first + s.spp; ++i) {
                Sampler sampler(s.sampler, s.seed, pixel, uint64_t(i));
                const float jx = sampler.get1D(), jy = sampler.get1D();
                const SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
                ts.tracking.setWavelengths(w);
                float time = 0.f;
                if (scene.camera.motionBlur()) {
                    time = shutterTime(scene.camera, s.seed, pixel, uint64_t(i));
                    ts.tracking.setTimeOffset(time);
                }
                const Ray ray =
                    scene.camera.moves()
                        ? PerspectiveCamera(scene.camera.poseAt(time), s.width, s.height)
                              .generate(float(x) + jx, float(y) + jy)
                        : camera.generate(float(x) + jx, float(y) + jy);
                if (ts.aov) aov.reset();
                if (ts.deep) deep.reset();
                std::optional<Sampler> data;
                std::optional<CameraRayData> record;
                if (walkCameraRay) {
                    data.emplace(SamplerKind::Random, dataSeed, pixel, uint64_t(i));
                    ts.cameraData = &record.emplace(scene, ray, w, *data, ts, ts.aov, ts.deep);
                }
                RadianceSample rs = integrator.Li(scene, ray, w, sampler, ts);
                if (achromatic) achromatic->apply(w, &rs);
                if (record) {
                    record->finish();
                    ts.cameraData = nullptr;
                    if (layout.coverage()) aov.scaleCoverage(rs.alpha);
                }
                const bool kept =
                    film->addSample(x - win.x0, y - win.y0, rs.L, w, rs.alpha, rs.xyz, ts.aov);
                if (ts.deep && kept) deepPixel.addSample(deep, w, rs.alpha);
            }
            if (!deepFilm) continue;
            deepFilm->setPixel(
                x, y, deepPixel.merge(s.deep, film->pixel(x - win.x0, y - win.y0).samples));
            deepPixel.clear();
        }
    ts.aov = nullptr;
    ts.deep = nullptr;
    return taken;
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
    const int tilesX = tileCountX(s);
    const int tiles = tileCount(s);
    Film film = checkpoint && checkpoint->initial
                    ? *checkpoint->initial
                    : Film(win.width(), win.height(), aovLayout(scene, s));
    MIRAGE_CHECK(film.width() == win.width() && film.height() == win.height());
    MIRAGE_CHECK(film.aovs().stride() == aovLayout(scene, s).stride());
    MIRAGE_CHECK(!pass.pixels || pass.pixels->size() == size_t(s.width) * size_t(s.height));
    // Deep pixels are numbered in the whole frame; the command refuses deep with a region.
    MIRAGE_CHECK(!deep || (win.width() == s.width && win.height() == s.height));
    PerspectiveCamera camera(scene.camera, s.width, s.height);
    // Colour exactly per sample where nothing in the scene is spectral; not with passes that
    // split each sample's spectral radiance (light paths, light groups) or deep samples, which
    // must sum to the beauty exactly. Data passes describe the camera ray, not its light: the
    // beauty keeps its exact colour (and its bits) with them.
    const std::optional<AchromaticFilm> achromatic =
        !film.aovs().splitsRadiance() && !deep ? AchromaticFilm::forScene(scene, integrator)
                                               : std::nullopt;

    // Which tiles are finished. A tile's pixels are written before its flag is stored (release)
    // and read by a checkpoint writer only after it loads the flag (acquire): no data race.
    std::unique_ptr<std::atomic<uint8_t>[]> done(new std::atomic<uint8_t>[size_t(tiles)]);
    int resumed = 0;
    for (int t = 0; t < tiles; ++t) {
        bool d = checkpoint && size_t(t) < checkpoint->done.size() && checkpoint->done[t];
        done[t].store(d ? 1 : 0, std::memory_order_relaxed);
        resumed += d;
    }
    auto snapshot = [&] {
        std::vector<uint8_t> v(size_t(tiles), 0);
        for (int t = 0; t < tiles; ++t) v[t] = done[t].load(std::memory_order_acquire);
        return v;
    };

    Progress progress("render", uint64_t(tiles), "tiles", s.progress);
    if (resumed > 0) progress.advance(uint64_t(resumed));
    std::atomic<uint64_t> lookups{0}, cappedFlights{0}, aboveMajorant{0}, samples{0};
    std::atomic<int64_t> finishedNow{0};
    std::mutex checkpointMutex;
    tbb::enumerable_thread_specific<ThreadState> states([&] { return ThreadState(scene); });

    // One tile per task (simple_partitioner, grain 1), so that an interrupt stops the hand-out
    // of tiles within one tile's time on every thread.
    tbb::parallel_for(
        tbb::blocked_range<int>(0, tiles, 1),
        [&](const tbb::blocked_range<int>& r) {
            ThreadState& ts = states.local();
            uint64_t before = ts.tracking.lookups, cappedBefore = ts.tracking.cappedFlights;
            uint64_t aboveBefore = ts.tracking.aboveMajorant;
            for (int tile = r.begin(); tile < r.end(); ++tile) {
                if (done[tile].load(std::memory_order_relaxed) || interruptRequested() ||
                    (checkpoint && std::chrono::steady_clock::now() >= checkpoint->deadline))
                    continue;
                samples += renderTile(scene, integrator, s, pass, camera, achromatic, tile, ts,
                                      &film, deep);
                done[tile].store(1, std::memory_order_release);
                progress.advance();
                int64_t n = ++finishedNow;
                if (checkpoint && checkpoint->stopAfterTiles >= 0 &&
                    n >= checkpoint->stopAfterTiles)
                    requestInterrupt(SIGINT);
                // A thread that finds the writer busy goes on rendering instead of waiting.
                if (checkpoint && checkpoint->tileFinished && checkpointMutex.try_lock()) {
                    std::lock_guard<std::mutex> lock(checkpointMutex, std::adopt_lock);
                    checkpoint->tileFinished(film, snapshot());
                }
            }
            lookups += ts.tracking.lookups - before;
            cappedFlights += ts.tracking.cappedFlights - cappedBefore;
            aboveMajorant += ts.tracking.aboveMajorant - aboveBefore;
        },
        tbb::simple_partitioner());
    progress.finish();

    std::vector<uint8_t> finalDone = snapshot();
    int tilesDone = 0;
    uint64_t pixelsDone = 0;
    for (int t = 0; t < tiles; ++t) {
        if (!finalDone[t]) continue;
        ++tilesDone;
        int x0 = (t % tilesX) * s.tileSize, y0 = (t / tilesX) * s.tileSize;
        pixelsDone += uint64_t(std::min(s.tileSize, win.width() - x0)) *
                      uint64_t(std::min(s.tileSize, win.height() - y0));
    }
    if (checkpoint) checkpoint->done = finalDone;
    if (stats) {
        stats->seconds = progress.elapsedSeconds();
        // With a pixel mask, the samples this pass took; else those the finished tiles hold.
        stats->samples = pass.pixels ? samples.load() : pixelsDone * uint64_t(s.spp);
        stats->mediumLookups = lookups.load();
        stats->nonFiniteSamples = film.nonFiniteSamples();
        stats->tiles = tiles;
        stats->tilesDone = tilesDone;
        stats->tilesResumed = resumed;
        stats->interrupted = tilesDone < tiles;
        stats->cappedFlights = cappedFlights.load();
        stats->aboveMajorant = aboveMajorant.load();
    }
    return film;
}

}  // namespace mirage
