// NanoVDB lookup and tracking throughput on a real cache (pipeline/bench.sh runs it on
// ../shared/data/vdb/smoke1.vdb). Prints medians of 5 runs; a program, not a test.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "transport/tracking.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

using namespace mirage;
using Clock = std::chrono::steady_clock;

static double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_lookups FILE.vdb [grid]\n");
        return 2;
    }
    try {
        auto t0 = Clock::now();
        FloatGrid grid = loadFloatGrid(argv[1], argc > 2 ? argv[2] : "density");
        double loadS = std::chrono::duration<double>(Clock::now() - t0).count();
        Bounds3 b = grid.objectBounds();
        std::printf("grid: %llu active voxels, NanoVDB %.1f MiB, load+convert %.3f s\n",
                    (unsigned long long)grid.activeVoxels(), grid.memoryBytes() / 1048576.0, loadS);

        // Random trilinear lookups inside the bounds (single thread).
        const int n = 4000000;
        std::vector<Vec3> pts(n);
        Sampler s(1, 0, 0);
        for (auto& p : pts)
            p = b.lo + b.diagonal() * Vec3(s.get1D(), s.get1D(), s.get1D());
        std::vector<double> rates;
        volatile float sink = 0;
        for (int run = 0; run < 5; ++run) {
            auto acc = grid.accessor();
            auto t = Clock::now();
            float sum = 0;
            for (const auto& p : pts) sum += grid.sample(acc, p);
            sink = sink + sum;
            rates.push_back(n / std::chrono::duration<double>(Clock::now() - t).count());
        }
        std::printf("random trilinear lookups: %.1f M/s (median of 5, 1 thread)\n",
                    median(rates) / 1e6);

        // Coherent lookups along rays, as the tracker makes them.
        ShaderDesc shader;
        shader.name = "bench";
        MediumComponent c;
        c.grid = "density";
        c.sigmaA = Spectrum(0.1f);
        c.sigmaS = Spectrum(1.5f);
        shader.components.push_back(c);
        auto t1 = Clock::now();
        Medium medium(shader, {grid}, Transform(), 1.f, 64);
        std::printf("majorant grid 64³ build: %.3f s\n",
                    std::chrono::duration<double>(Clock::now() - t1).count());
        TrackingContext ctx({&medium});
        std::vector<double> trackRates;
        for (int run = 0; run < 5; ++run) {
            uint64_t before = ctx.lookups;
            auto t = Clock::now();
            for (int i = 0; i < 20000; ++i) {
                Sampler rs(2, uint64_t(i), uint64_t(run));
                ctx.setWavelengths(SampledWavelengths::sampleVisible(rs.get1D()));
                Vec3 o = b.center() + Vec3(0, 0, 200);
                Vec3 target = b.lo + b.diagonal() * Vec3(rs.get1D(), rs.get1D(), 0.5f);
                Ray r{o, normalize(target - o), kInfinity};
                transmittance(ctx, r, kInfinity, rs);
            }
            double dt = std::chrono::duration<double>(Clock::now() - t).count();
            trackRates.push_back((ctx.lookups - before) / dt);
        }
        std::printf("ratio-tracking medium lookups: %.1f M/s (median of 5, 1 thread)\n",
                    median(trackRates) / 1e6);
    } catch (const MirageError& e) {
        std::fprintf(stderr, "bench_lookups: %s\n", e.what());
        return 1;
    }
    return 0;
}
