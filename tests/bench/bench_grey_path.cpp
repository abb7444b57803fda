// The grey path against the spectral path ("model only what a scene requires", medium.h): the
// same grey scene — the procedural fog sphere (mirage make-asset fog-sphere, resolution 64,
// σa 0.1, σs 4 per unit density, HG 0.3) under a 5800 K sun — rendered by volpath (96×96,
// 32 spp) and traced by the photon pass (3·10⁵ photons), once with Medium::setGreyPath(true)
// and once forced spectral. One thread, process CPU time (the machine may be shared: CPU time
// is steadier than wall time), median of 5 runs of each, alternated; prints their ratio and
// the largest pixel difference. A program, not a test.
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <vector>

#include "core/error.h"
#include "film/color.h"
#include "photon/photon_pass.h"
#include "render/renderer.h"
#include "tools/asset_writer.h"
#include "volume/vdb_file.h"

using namespace mirage;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

double cpuSeconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

int main() {
    try {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
        const std::string path =
            (std::filesystem::temp_directory_path() / "mirage_bench_grey_fog.vdb").string();
        writeProceduralAsset("fog-sphere", path, 64, 1);
        FloatGrid grid = loadFloatGrid(path, "density");
        ShaderDesc shader;
        shader.name = "grey";
        MediumComponent c;
        c.name = "fog";
        c.grid = "density";
        c.sigmaA = Spectrum(0.1f);
        c.sigmaS = Spectrum(4.f);
        c.g = 0.3f;
        shader.components.push_back(c);

        RenderScene scene[2];  // 0: grey path, 1: forced spectral
        for (int s = 0; s < 2; ++s) {
            scene[s].media.push_back(std::make_unique<Medium>(shader, std::vector<FloatGrid>{grid},
                                                              Transform(), 1.f, 64));
            scene[s].media[0]->setGreyPath(s == 0);
            scene[s].lights.push_back(makeDistantLight(normalize(Vec3(0.6f, -0.7f, -0.4f)), 1476.f,
                                                       blackbodyNormalized(5800.f)));
            scene[s].camera.position = Vec3(0.f, 1.f, 3.2f);
            scene[s].camera.lookAt = Vec3(0.f, 1.f, 0.f);
            scene[s].camera.fovDeg = 40.f;
        }
        RenderSettings rs;
        rs.width = rs.height = 96;
        rs.spp = 32;
        rs.seed = 1;
        rs.progress = Progress::Mode::Quiet;
        ColorPipeline color;
        std::vector<double> renderSeconds[2], photonSeconds[2];
        Image images[2];
        for (int run = 0; run < 5; ++run)
            for (int s = 0; s < 2; ++s) {
                auto volpath = makeVolPathIntegrator();
                double t0 = cpuSeconds();
                Film film = render(scene[s], *volpath, rs, nullptr);
                renderSeconds[s].push_back(cpuSeconds() - t0);
                images[s] = film.develop(color);

                PhotonPassSettings ps;
                ps.photons = 300000;
                ps.seed = uint64_t(run);
                ps.progress = Progress::Mode::Quiet;
                PhotonPassStats stats;
                double t1 = cpuSeconds();
                tracePhotons({scene[s].lights[0].get()}, {scene[s].media[0].get()}, ps, &stats);
                photonSeconds[s].push_back(cpuSeconds() - t1);
            }
        double maxDiff = 0.0, sum = 0.0;
        for (size_t i = 0; i < images[0].rgba.size(); ++i) {
            maxDiff = std::max(maxDiff, double(std::abs(images[0].rgba[i] - images[1].rgba[i])));
            sum += images[1].rgba[i];
        }
        const double rg = median(renderSeconds[0]), rsp = median(renderSeconds[1]);
        const double pg = median(photonSeconds[0]), psp = median(photonSeconds[1]);
        std::printf(
            "volpath 96x96, 32 spp, 1 thread: grey %.3f s, spectral %.3f s CPU, "
            "spectral/grey %.3f\n",
            rg, rsp, rsp / rg);
        std::printf(
            "photon pass, 3e5 photons, 1 thread: grey %.3f s, spectral %.3f s CPU, "
            "spectral/grey %.3f\n",
            pg, psp, psp / pg);
        std::printf("largest pixel difference %.3g (image mean %.3g)\n", maxDiff,
                    sum / double(images[1].rgba.size()));
        std::filesystem::remove(path);
    } catch (const MirageError& e) {
        std::fprintf(stderr, "bench_grey_path: %s\n", e.what());
        return 1;
    }
    return 0;
}
