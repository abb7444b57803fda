#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>

namespace mirage {

Film render(const RenderScene& scene, Integrator& integrator, const RenderSettings& s,
            RenderStats* stats) {
    Film film(s.width, s.height);
    PerspectiveCamera camera(scene.camera, s.width, s.height);
    const int tilesX = (s.width + s.tileSize - 1) / s.tileSize;
    const int tilesY = (s.height + s.tileSize - 1) / s.tileSize;
    const int tiles = tilesX * tilesY;

    Progress progress("render", uint64_t(tiles), "tiles", s.progress);
    std::atomic<uint64_t> lookups{0}, cappedFlights{0};
    tbb::enumerable_thread_specific<ThreadState> states([&] { return ThreadState(scene); });

    tbb::parallel_for(tbb::blocked_range<int>(0, tiles, 1), [&](const tbb::blocked_range<int>& r) {
        ThreadState& ts = states.local();
        uint64_t before = ts.tracking.lookups, cappedBefore = ts.tracking.cappedFlights;
        for (int tile = r.begin(); tile < r.end(); ++tile) {
            int x0 = (tile % tilesX) * s.tileSize, y0 = (tile / tilesX) * s.tileSize;
            int x1 = std::min(x0 + s.tileSize, s.width), y1 = std::min(y0 + s.tileSize, s.height);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    uint64_t pixel = uint64_t(y) * uint64_t(s.width) + uint64_t(x);
                    for (int i = 0; i < s.spp; ++i) {
                        Sampler sampler(s.seed, pixel, uint64_t(i));
                        float jx = sampler.get1D(), jy = sampler.get1D();
                        SampledWavelengths w = SampledWavelengths::sampleVisible(sampler.get1D());
                        ts.tracking.setWavelengths(w);
                        Ray ray = camera.generate(float(x) + jx, float(y) + jy);
                        RadianceSample rs = integrator.Li(scene, ray, w, sampler, ts);
                        film.addSample(x, y, rs.L, w, rs.alpha, rs.xyz);
                    }
                }
            progress.advance();
        }
        lookups += ts.tracking.lookups - before;
        cappedFlights += ts.tracking.cappedFlights - cappedBefore;
    });
    progress.finish();

    if (stats) {
        stats->seconds = progress.elapsedSeconds();
        stats->samples = uint64_t(s.width) * s.height * s.spp;
        stats->mediumLookups = lookups.load();
        stats->nonFiniteSamples = film.nonFiniteSamples();
        stats->cappedFlights = cappedFlights.load();
    }
    return film;
}

}  // namespace mirage
