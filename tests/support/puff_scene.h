// The moving puff of the motion-blur tests: a soft ball of density with a constant velocity
// grid, its scenes, renders, and the comparison of a blurred render with the mean of stills
// spread over the shutter (per band of columns, against the standard error of replicates).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "film/color.h"
#include "render/integrator.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "test_grids.h"

namespace mirage {
namespace puff {

constexpr double kVoxel = 0.05;  // m
constexpr double kPuffRadius = 0.25;
constexpr double kSpeed = 2.0;    // m/s along +x
constexpr double kFps = 2.0;      // the scene's frame rate
constexpr double kShutter = 1.0;  // frames, centred: Δt in [-0.25, 0.25] s, blur 1 m

// A soft ball of density at the origin and a constant velocity over a box that holds every
// point the ball reaches within the shutter (plus the trilinear stencil).
inline std::string writePuff(const std::string& dir, Vec3d velocity = Vec3d(kSpeed, 0, 0),
                             const std::string& velName = "vel") {
    TestGridSpec density;
    density.voxelSize = kVoxel;
    const int r = int(std::ceil(kPuffRadius / kVoxel));
    for (int i = -r; i <= r; ++i)
        for (int j = -r; j <= r; ++j)
            for (int k = -r; k <= r; ++k) {
                const double d2 =
                    (i * i + j * j + k * k) * kVoxel * kVoxel / (kPuffRadius * kPuffRadius);
                if (d2 < 1.0) density.voxels.push_back({i, j, k, (1 - d2) * (1 - d2)});
            }
    TestGridSpec vel;
    vel.name = velName;
    vel.valueType = "vec3s";
    vel.gridClass = "unknown";
    vel.voxelSize = kVoxel;
    const int reachX = r + int(std::ceil(0.5 * kShutter / kFps * kSpeed / kVoxel)) + 2;
    for (int i = -reachX; i <= reachX; ++i)
        for (int j = -r - 2; j <= r + 2; ++j)
            for (int k = -r - 2; k <= r + 2; ++k) vel.voxels.push_back({i, j, k, 0.0, velocity});
    const std::string path = dir + "/puff.vdb";
    writeTestGrids(path, {density, vel});
    return path;
}

inline const std::string kOpen = "[-0.5, 0.5]";  // kShutter frames, centred
inline const std::string kStill = "velocity = \"\"\n";

// A scene of the puff: its shutter ("[open, close]" frames, "" for none), the volume's extra
// keys, its translation dx and transform keys, the camera's table body and its keys.
struct PuffScene {
    std::string shutter, volumeKeys;
    double dx = 0;
    std::string transformKeys;  // [[volume.transform.key]] tables
    std::string camera = "position = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 25\n";
    std::string cameraKeys;  // [[camera.key]] tables
    std::string extra;       // more top-level tables
};

// The puff held still (its velocity unbound) with `shutter`: what moves is the camera or the
// volume's transform.
inline PuffScene stillPuff(const std::string& shutter = "") {
    PuffScene p;
    p.shutter = shutter;
    p.volumeKeys = kStill;
    return p;
}

inline std::string writePuffScene(const std::string& dir, const std::string& name,
                                  const PuffScene& p) {
    const std::string path = dir + "/" + name + ".toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [48, 24]\nspp = 32\ntile_size = 8\n"
      << "[camera]\n"
      << p.camera;
    if (!p.shutter.empty()) f << "shutter = " << p.shutter << "\n";
    f << p.cameraKeys << "[output]\nfps = " << kFps << "\n"
      << "[[volume]]\nfile = \"puff.vdb\"\ndensity_scale = 6\n"
      << p.volumeKeys << "[volume.transform]\ntranslate = [" << p.dx << ", 0, 0]\n"
      << p.transformKeys << "[[light]]\ntype = \"sun\"\ndirection = [0.6, -1, -0.5]\n"
      << p.extra;
    return path;
}

// The puff with `shutter` and the volume's extra keys, translated by dx.
inline std::string writeScene(const std::string& dir, const std::string& name,
                              const std::string& shutter, const std::string& volumeKeys,
                              double dx = 0) {
    PuffScene p;
    p.shutter = shutter;
    p.volumeKeys = volumeKeys;
    p.dx = dx;
    return writePuffScene(dir, name, p);
}

// Keys at frames 0 and 2 (±0.5 s about frame 1) moving the camera, or the puff, from x = −1 m
// to 1 m: within the shutter kOpen (±0.25 s) they move by ±kHalfPan.
inline const std::string kPanKeys =
    "[[camera.key]]\nframe = 0\nposition = [-1, 0, 4]\nlook_at = [-1, 0, 0]\n"
    "[[camera.key]]\nframe = 2\nposition = [1, 0, 4]\nlook_at = [1, 0, 0]\n";
inline const std::string kTranslateKeys =
    "[[volume.transform.key]]\nframe = 0\ntranslate = [-1, 0, 0]\n"
    "[[volume.transform.key]]\nframe = 2\ntranslate = [1, 0, 0]\n";
constexpr double kHalfPan = 0.5;  // m

// Renders a loaded scene with its own settings, quietly, for its statistics.
inline RenderStats renderStats(const Scene& scene, const std::string& integrator) {
    auto in = makeIntegrator(integrator);
    in->preprocess(scene.render);
    RenderSettings s = scene.settings;
    s.progress = Progress::Mode::Quiet;
    RenderStats stats;
    render(scene.render, *in, s, &stats);
    return stats;
}

struct Rendered {
    std::vector<double> Y;  // per pixel, mean luminance-like Y
    RenderStats stats;
    Film film{1, 1};
};

// The scene at `path` rendered with `seed`, at `spp` samples per pixel (0: the scene's own).
inline Rendered renderScene(const std::string& path, uint64_t seed, const std::string& integrator,
                            int spp = 0) {
    ColorPipeline color;
    Scene scene = loadScene(path, LoadOptions{}, color);
    RenderSettings s = scene.settings;
    s.seed = seed;
    if (spp > 0) s.spp = spp;
    s.progress = Progress::Mode::Quiet;
    auto in = makeIntegrator(integrator);
    in->preprocess(scene.render);
    Rendered r;
    r.film = render(scene.render, *in, s, &r.stats);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const Film::Pixel& p = r.film.pixel(x, y);
            r.Y.push_back(p.samples ? p.xyz[1] / p.samples : 0.0);
        }
    return r;
}

// Per pixel: the mean over replicate renders and the variance of that mean.
struct Estimate {
    std::vector<double> mean, var;
};
inline Estimate combine(const std::vector<std::vector<double>>& reps) {
    const size_t n = reps[0].size(), R = reps.size();
    Estimate e{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
    for (size_t i = 0; i < n; ++i) {
        for (const auto& r : reps) e.mean[i] += r[i] / double(R);
        for (const auto& r : reps) e.var[i] += (r[i] - e.mean[i]) * (r[i] - e.mean[i]);
        e.var[i] /= double(R - 1) * double(R);
    }
    return e;
}

// The largest |z| over bands of 4 columns of Σ (a − b) against its standard error: the blur
// is along x, so the columns carry the profile being compared; bands pool the image's fringe,
// where a column's few covered samples make its variance estimate unreliable.
inline double worstColumnZ(const Estimate& a, const Estimate& b, int width, int height) {
    constexpr int kBand = 4;
    double worst = 0.0;
    for (int x0 = 0; x0 < width; x0 += kBand) {
        double d = 0.0, v = 0.0;
        for (int x = x0; x < std::min(width, x0 + kBand); ++x)
            for (int y = 0; y < height; ++y) {
                const size_t i = size_t(y) * width + x;
                d += a.mean[i] - b.mean[i];
                v += a.var[i] + b.var[i];
            }
        if (v > 0.0)
            worst = std::max(worst, std::abs(d) / std::sqrt(v));
        else
            EXPECT_EQ(d, 0.0) << "columns " << x0 << "+";
    }
    return worst;
}

// The samples per pixel of each of N stills in one replicate of a mean of stills: together
// 8 times the blurred render's 32 (writePuffScene), never more than 32 each. The mean of stills
// then has at most an eighth of the blurred render's variance (a still's per-sample variance
// lacks the blur's spread over time), and the comparison's σ is at most √(1 + 1/8) = 1.061
// times the blurred render's own. At 32 spp for each of N = 32 stills it was 1.016 times: 4 %
// narrower for 4 times the samples, most of the test's time.
inline int stillSpp(int N) { return std::min(32, (256 + N - 1) / N); }

// The mean of still renders of the puff translated to N offsets spread evenly (midpoints)
// over [-halfLength, halfLength], `reps` replicates with independent seeds. The midpoint rule
// leaves out the last half step at each end of the blur: N = 32 keeps that below the noise.
// The same for any still: stillAt(u) writes the scene of the still at u in (-1, 1), the
// midpoints of N equal steps over the shutter.
inline Estimate meanOfStills(const std::function<std::string(double)>& stillAt, int reps,
                             uint64_t seed0, const std::string& integrator, int N = 32) {
    std::vector<std::vector<double>> out;
    for (int r = 0; r < reps; ++r) {
        std::vector<double> sum;
        for (int k = 0; k < N; ++k) {
            const double u = -1.0 + (k + 0.5) / N * 2.0;
            Rendered still =
                renderScene(stillAt(u), seed0 + uint64_t(r * N + k), integrator, stillSpp(N));
            if (sum.empty()) sum.assign(still.Y.size(), 0.0);
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += still.Y[i] / N;
        }
        out.push_back(sum);
    }
    return combine(out);
}

inline Estimate stillComposite(const std::string& dir, double halfLength, int reps, uint64_t seed0,
                               const std::string& integrator, int N = 32) {
    return meanOfStills(
        [&](double u) { return writeScene(dir, "still", "", kStill, u * halfLength); }, reps, seed0,
        integrator, N);
}

inline bool sameFilm(const Film& a, const Film& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            if (std::memcmp(&a.pixel(x, y), &b.pixel(x, y), sizeof(Film::Pixel)) != 0) return false;
    return true;
}

}  // namespace puff
}  // namespace mirage
