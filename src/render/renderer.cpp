#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <atomic>
#include <csignal>
#include <memory>
#include <mutex>

#include "core/error.h"
#include "core/interrupt.h"
#include "render/camera_ray_data.h"

namespace mirage {

namespace {

// Every sample of one tile's pixels into the film (tiles do not overlap: no two threads write
// one pixel). A sample's numbers come from its own (seed, pixel, sample): pixel jitter, its
// wavelengths, then the integrator's; its time in the shutter from a stream of its own, so
// that a closed shutter leaves every other number where it was. With AOVs, ts.aov collects
// each sample's passes, and the camera ray's data passes take numbers of their own too.
void renderTile(const RenderScene& scene, const Integrator& integrator, const RenderSettings& s,
                const PerspectiveCamera& camera, int tile, ThreadState& ts, Film* film,
                DeepFilm* deepFilm) {
    const AovLayout& layout = film->aovs();
    AovSample aov(layout.groupSlots());
    ts.aov = layout.empty() ? nullptr : &aov;
    ts.lightSplit.assign(size_t(layout.groupSlots()), SampledSpectrum(0.f));
    DeepSample deep;
    DeepPixel deepPixel;
    ts.deep = deepFilm ? &deep : nullptr;
    const bool walkCameraRay = layout.cameraData() || deepFilm;
    const uint64_t dataSeed = hashCombine(s.seed, 0x616f7664617461ull);  // "aovdata"
    const int tilesX = tileCountX(s);
    const int x0 = (tile % tilesX) * s.tileSize, y0 = (tile / tilesX) * s.tileSize;
    const int x1 = std::min(x0 + s.tileSize, s.width), y1 = std::min(y0 + s.tileSize, s.height);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const uint64_t pixel = uint64_t(y) * uint64_t(s.width) + uint64_t(x);
            for (int i = 0; i < s.spp; ++i) {
                Sampler sampler(s.sampler, s.seed, pixel, uint64_t(i));
                const float jx = sampler.get1D(), jy = sampler.get1D();
                const SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
                ts.tracking.setWavelengths(w);
                if (scene.camera.motionBlur())
                    ts.tracking.setTimeOffset(shutterTime(scene.camera, s.seed, pixel, uint64_t(i)));
                const Ray ray = camera.generate(float(x) + jx, float(y) + jy);
                if (ts.aov) aov.reset();
                if (ts.deep) deep.reset();
                const RadianceSample rs = integrator.Li(scene, ray, w, sampler, ts);
                if (walkCameraRay) {
                    Sampler data(SamplerKind::Random, dataSeed, pixel, uint64_t(i));
                    cameraRayData(scene, ray, data, ts, ts.aov, ts.deep);
                }
                const bool kept = film->addSample(x, y, rs.L, w, rs.alpha, rs.xyz, ts.aov);
                if (ts.deep && kept) deepPixel.addSample(deep, w, rs.alpha);
            }
            if (!deepFilm) continue;
            deepFilm->setPixel(x, y, deepPixel.merge(s.deep, film->pixel(x, y).samples));
            deepPixel.clear();
        }
    ts.aov = nullptr;
    ts.deep = nullptr;
}

}  // namespace

AovLayout aovLayout(const RenderScene& scene, const RenderSettings& s, const IntegratorInfo& info) {
    AovLayout layout(s.aovs, scene.lightGroupNames());
    if (layout.groupSlots() > 0 && info.photonPass)
        throw MirageError(
            "light-group passes (lightgroup_*) need an integrator without a photon "
            "pass: photons do not record which light they came from; the " +
            info.name + " integrator has one (use single or volpath)");
    return layout;
}

Film render(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
            RenderStats* stats, TileCheckpoint* checkpoint, DeepFilm* deep) {
    const int tilesX = tileCountX(s);
    const int tiles = tileCount(s);
    Film film = checkpoint && checkpoint->initial
                    ? *checkpoint->initial
                    : Film(s.width, s.height, aovLayout(scene, s, integrator.info()));
    MIRAGE_CHECK(film.width() == s.width && film.height() == s.height);
    MIRAGE_CHECK(film.aovs().stride() == aovLayout(scene, s, integrator.info()).stride());
    PerspectiveCamera camera(scene.camera, s.width, s.height);

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
    std::atomic<uint64_t> lookups{0}, cappedFlights{0}, aboveMajorant{0};
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
                if (done[tile].load(std::memory_order_relaxed) || interruptRequested()) continue;
                renderTile(scene, integrator, s, camera, tile, ts, &film, deep);
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
        pixelsDone += uint64_t(std::min(s.tileSize, s.width - x0)) *
                      uint64_t(std::min(s.tileSize, s.height - y0));
    }
    if (checkpoint) checkpoint->done = finalDone;
    if (stats) {
        stats->seconds = progress.elapsedSeconds();
        stats->samples = pixelsDone * uint64_t(s.spp);
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
