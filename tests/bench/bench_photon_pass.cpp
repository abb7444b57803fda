// Photon-pass throughput: emitted and stored photons per second, on 1 thread and on all.
// Without arguments the scene is a homogeneous fog box (2 m, σt = 5/m, albedo 0.9) around a
// point light; with FILE.vdb [grid] it is that cache (σa = 0.1, σs = 1.5 per unit density)
// lit by a distant light from above. Prints medians of 3 runs; a program, not a test.
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "core/error.h"
#include "photon/photon_pass.h"
#include "volume/vdb_file.h"

using namespace mirage;

namespace {

void run(const char* label, const std::vector<const Light*>& lights,
         const std::vector<const Medium*>& media, uint64_t photons, size_t threads) {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
    PhotonPassSettings ps;
    ps.photons = photons;
    ps.progress = Progress::Mode::Quiet;
    std::vector<double> seconds;
    PhotonPassStats stats;
    for (int i = 0; i < 3; ++i) {
        ps.seed = uint64_t(i);
        tracePhotons(lights, media, ps, &stats);
        seconds.push_back(stats.seconds);
    }
    std::sort(seconds.begin(), seconds.end());
    double s = seconds[1];
    std::printf(
        "%s, %zu thread(s): %.3f s, %.2f M emitted/s, %.2f M stored/s (%.2f stored per "
        "emitted)\n",
        label, threads, s, photons / s * 1e-6, stats.stored / s * 1e-6,
        double(stats.stored) / photons);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        ShaderDesc shader;
        shader.name = "bench";
        MediumComponent c;
        c.name = "bench";
        std::unique_ptr<Medium> medium;
        std::unique_ptr<Light> light;
        const char* label;
        if (argc > 1) {
            FloatGrid grid = loadFloatGrid(argv[1], argc > 2 ? argv[2] : "density");
            c.grid = "density";
            c.sigmaA = Spectrum(0.1f);
            c.sigmaS = Spectrum(1.5f);
            shader.components.push_back(c);
            medium = std::make_unique<Medium>(shader, std::vector<FloatGrid>{grid}, Transform(),
                                              1.f, 64);
            light = makeDistantLight(Vec3(0.2f, -1.f, 0.1f), 1.f, Spectrum(1.f));
            label = argv[1];
        } else {
            c.sigmaA = Spectrum(0.5f);
            c.sigmaS = Spectrum(4.5f);
            shader.components.push_back(c);
            Bounds3 b;
            b.lo = Vec3(-1.f);
            b.hi = Vec3(1.f);
            medium = std::make_unique<Medium>(shader, b, Transform(), 1.f);
            light = makePointLight(Vec3(0.f), 100.f, Spectrum(1.f));
            label = "homogeneous fog box";
        }
        const uint64_t photons = 1000000;
        for (size_t threads : {size_t(1), size_t(0)}) {
            size_t t = threads ? threads
                               : size_t(tbb::global_control::active_value(
                                     tbb::global_control::max_allowed_parallelism));
            run(label, {light.get()}, {medium.get()}, photons, t);
        }
    } catch (const MirageError& e) {
        std::fprintf(stderr, "bench_photon_pass: %s\n", e.what());
        return 1;
    }
    return 0;
}
