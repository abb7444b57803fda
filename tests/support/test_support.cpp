#include "test_support.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "film/image_io.h"
#include "fog_box_scene.h"
#include "volume/grid_lookup.h"

namespace mirage::test {

std::string mirageBinary() { return MIRAGE_BINARY; }
std::string sourceDir() { return MIRAGE_SOURCE_DIR; }

std::string sharedData() {
    std::error_code ec;
    return std::filesystem::is_directory(MIRAGE_SHARED_DATA, ec) ? std::string(MIRAGE_SHARED_DATA)
                                                                 : std::string();
}

std::string sharedFile(const std::string& relative) {
    std::string root = sharedData();
    if (root.empty()) return {};
    std::string p = root + "/" + relative;
    std::error_code ec;
    return std::filesystem::exists(p, ec) ? p : std::string();
}

std::string makeFogSphere(const std::string& dir, int resolution) {
    std::string log;
    EXPECT_EQ(runMirage("make-asset fog-sphere -o '" + dir + "/fog.vdb' --resolution " +
                            std::to_string(resolution),
                        &log),
              0)
        << log;
    return dir + "/fog.vdb";
}

std::string writeFogSphereScene(const std::string& dir, const std::string& film,
                                const std::string& render, const std::string& light) {
    makeFogSphere(dir);
    std::ofstream f(dir + "/scene.toml");
    f << "[film]\n"
      << film << "\n[render]\n"
      << render << "\n"
      << "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 35\n"
         "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3\n"
         "[[light]]\n"
      << (light.empty() ? "type = \"sun\"\ndirection = [0.6, -0.7, -0.4]\nirradiance = 1476\n"
                        : light + "\n");
    return dir + "/scene.toml";
}

std::string writeSunnySky(const std::string& dir) {
    const std::string path = dir + "/sunny.hdr";
    std::ofstream hdr(path, std::ios::binary);
    hdr << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n";
    for (int p = 0; p < 32 * 16; ++p) {
        const bool sunPixel = p == 4 * 32 + 11;
        const char m = char(sunPixel ? 150 : 204), e = char(sunPixel ? 137 : 126);
        hdr << m << m << m << e;  // 300 = 150/256 × 2^9, 0.2 = 204/256 × 2^−2
    }
    return path;
}

std::string shippedScene(const std::string& name) {
    return (std::filesystem::path(MIRAGE_SOURCE_DIR) / "assets" / "scenes" / name)
        .lexically_normal()
        .string();
}

std::string shippedSceneCopy(const std::string& dir, const std::string& name,
                             const std::string& asset, const std::string& file, int resolution) {
    const std::string copy = dir + "/" + name;
    std::error_code ec;
    std::filesystem::copy_file(shippedScene(name), copy,
                               std::filesystem::copy_options::overwrite_existing, ec);
    EXPECT_FALSE(ec) << "copying " << shippedScene(name) << ": " << ec.message();
    if (!asset.empty()) {
        std::string log;
        EXPECT_EQ(runMirage("make-asset " + asset + " -o '" + dir + "/" + file + "' --resolution " +
                                std::to_string(resolution),
                            &log),
                  0)
            << log;
    }
    return copy;
}

std::string tempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "mirage";
    auto dir = std::filesystem::temp_directory_path() /
               ("mirage_test_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

int runCommand(const std::string& cmd, std::string* output) {
    std::string full = cmd + " 2>&1";
    FILE* pipe = ::popen(full.c_str(), "r");
    if (!pipe) return -1;
    std::array<char, 4096> buf;
    std::string out;
    size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
    int status = ::pclose(pipe);
    if (output) *output = out;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

int runMirage(const std::string& args, std::string* output) {
    return runCommand(std::string("'") + MIRAGE_BINARY + "' " + args, output);
}

std::map<std::string, std::string> renderMetadata(const std::string& scene, const std::string& args,
                                                  const std::string& exr) {
    std::string out;
    EXPECT_EQ(
        0, runMirage("render '" + scene + "' -q --threads 2 " + args + " -o '" + exr + "'", &out))
        << out;
    std::map<std::string, std::string> meta;
    readExr(exr, &meta);
    return meta;
}

}  // namespace mirage::test

#include <nanovdb/util/GridBuilder.h>

namespace mirage::test {

FloatGrid makeGrid(const std::function<float(int, int, int)>& value, int lo, int hi, double h,
                   const Vec3d& origin, const std::string& name) {
    // NanoVDB's GridBuilder left-shifts coordinates, which for a negative index is undefined
    // behaviour (UBSan stops the sanitizer gate on it): place a grid by its origin instead.
    if (lo < 0)
        throw std::invalid_argument("test::makeGrid: lo must be >= 0, not " + std::to_string(lo));
    nanovdb::GridBuilder<float> builder(0.f, nanovdb::GridClass::FogVolume);
    builder([&](const nanovdb::Coord& c) { return value(c[0], c[1], c[2]); },
            nanovdb::CoordBBox(nanovdb::Coord(lo), nanovdb::Coord(hi)));
    auto handle = builder.getHandle<>(h, nanovdb::Vec3d(origin.x, origin.y, origin.z), name);
    return FloatGrid(std::move(handle), name);
}

ShaderDesc greyShader(float sigmaA, float sigmaS, float g) {
    ShaderDesc s;
    s.name = "test";
    MediumComponent c;
    c.grid = "density";
    c.sigmaA = Spectrum(sigmaA);
    c.sigmaS = Spectrum(sigmaS);
    c.g = g;
    s.components.push_back(c);
    return s;
}

ShaderDesc glowingShader(float sigmaA, float sigmaS, float g) {
    ShaderDesc s = greyShader(sigmaA, sigmaS, g);
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    s.emission = e;
    return s;
}

double opticalDepth(const FloatGrid& g, const Vec3& a, const Vec3& b, double sigmaT) {
    auto acc = g.accessor();
    const int n = 2000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += g.sample(acc, a + (b - a) * ((i + 0.5f) / n));
    return sigmaT * sum * length(b - a) / n;
}

double quadratureAlongRay(const FloatGrid& g, const Ray& ray, double t0, double t1, double nearest,
                          double D, double sigmaT, const std::function<double(const Vec3&)>& f) {
    auto acc = g.accessor();
    const double ta = std::atan((t0 - nearest) / D), tb = std::atan((t1 - nearest) / D);
    const int n = 8000;
    double sum = 0.0, tau = 0.0, tPrev = t0;
    for (int i = 0; i < n; ++i) {
        const double theta = ta + (tb - ta) * (i + 0.5) / n;
        const double t = nearest + D * std::tan(theta);
        tau += sigmaT * g.sample(acc, ray.at(float(0.5 * (t + tPrev)))) * (t - tPrev);
        tPrev = t;
        sum += std::exp(-tau) * f(ray.at(float(t))) * D / (std::cos(theta) * std::cos(theta));
    }
    return sum * (tb - ta) / n;
}

RenderScene unitCubeScene(float sigmaS, float g) {
    RenderScene scene;
    scene.media.push_back(gridMedium([](int, int, int) { return 1.f; }, 0, 15, 0.125, 0.f, sigmaS,
                                     g, Transform::translate(Vec3d(-1.0))));
    return scene;
}

LatLongImage flatSky(int width, int height, float value) {
    LatLongImage img;
    img.width = width;
    img.height = height;
    img.rgb.assign(size_t(width) * size_t(height) * 3, value);
    return img;
}

void expectBothNear(const char* what, double expected, const RayEstimate& equiangular,
                    const RayEstimate& distance) {
    std::printf(
        "%s: expected %.5g; equiangular %.5g ± %.2g (largest %.1f × mean); distance "
        "%.5g ± %.2g (largest %.1f × mean)\n",
        what, expected, equiangular.mean, equiangular.se, equiangular.largest / equiangular.mean,
        distance.mean, distance.se, distance.largest / distance.mean);
    EXPECT_NEAR(equiangular.mean, expected, 4 * equiangular.se + 0.01 * expected) << what;
    EXPECT_NEAR(distance.mean, expected, 4 * distance.se + 0.01 * expected) << what;
}

std::unique_ptr<Medium> gridMedium(const std::function<float(int, int, int)>& value, int lo, int hi,
                                   double h, float sigmaA, float sigmaS, float g,
                                   const Transform& objectToWorld) {
    std::vector<FloatGrid> grids{makeGrid(value, lo, hi, h)};
    return std::make_unique<Medium>(greyShader(sigmaA, sigmaS, g), std::move(grids), objectToWorld,
                                    1.f, 16);
}

RenderScene fogBoxScene() {
    RenderScene scene;
    scene.media.push_back(
        gridMedium([](int, int, int) { return 1.f; }, 0, 31, 1.0 / 32, 0.4f, 4.f, 0.3f));
    scene.lights.push_back(
        makeDistantLight(normalize(Vec3(0.3f, -1.f, -0.2f)), 1000.f, Spectrum(1.f)));
    scene.camera.position = Vec3(0.5f, 0.6f, 3.f);
    scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
    scene.camera.fovDeg = 26.f;
    return scene;
}

RenderSettings smallRenderSettings(int spp, uint64_t seed, int width, int height) {
    RenderSettings rs;
    rs.width = width;
    rs.height = height;
    rs.tileSize = 8;
    rs.spp = spp;
    rs.seed = seed;
    rs.progress = Progress::Mode::Quiet;
    return rs;
}

RenderScene sunlitSmokeBox() {
    RenderScene scene;
    scene.media.push_back(gridMedium(
        [](int i, int j, int k) { return 0.5f + 0.5f * std::sin(0.4f * i + 0.3f * j + 0.2f * k); },
        0, 15, 1.0 / 16, 0.5f, 4.f, 0.3f));
    scene.lights.push_back(makeDistantLight(Vec3(0.3f, -1, 0.2f), 470.f, Spectrum(1.f)));
    scene.camera.position = Vec3(0.5f, 0.5f, 3.f);
    scene.camera.lookAt = Vec3(0.5f, 0.5f, 0.5f);
    scene.camera.fovDeg = 30.f;
    return scene;
}

RayEstimate estimateAlongRay(const Integrator& integrator, const RenderScene& scene, const Ray& ray,
                             int samples) {
    return estimateAlongRayPerWavelength(integrator, scene, ray, samples)[0];
}

std::array<RayEstimate, kSpectrumSamples> estimateAlongRayPerWavelength(
    const Integrator& integrator, const RenderScene& scene, const Ray& ray, int samples) {
    ThreadState ts(scene);
    std::array<double, kSpectrumSamples> sum{}, sum2{}, largest{};
    for (int i = 0; i < samples; ++i) {
        Sampler s(SamplerKind::Random, 1, 0, uint64_t(i));
        SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
        ts.tracking.setWavelengths(w);
        const SampledSpectrum L = integrator.Li(scene, ray, w, s, ts).L;
        for (int k = 0; k < kSpectrumSamples; ++k) {
            sum[k] += L[k];
            sum2[k] += double(L[k]) * L[k];
            largest[k] = std::max(largest[k], double(L[k]));
        }
    }
    std::array<RayEstimate, kSpectrumSamples> out;
    for (int k = 0; k < kSpectrumSamples; ++k) {
        const double mean = sum[k] / samples;
        out[k] = {mean, std::sqrt(std::max(0.0, sum2[k] / samples - mean * mean) / samples),
                  largest[k]};
    }
    return out;
}

bool sameFilm(const Film& a, const Film& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const Film::Pixel &p = a.pixel(x, y), &q = b.pixel(x, y);
            if (std::memcmp(p.xyz, q.xyz, sizeof p.xyz) != 0 ||
                std::memcmp(p.xyzSq, q.xyzSq, sizeof p.xyzSq) != 0 ||
                std::memcmp(&p.alpha, &q.alpha, sizeof p.alpha) != 0 || p.samples != q.samples)
                return false;
        }
    return true;
}

ImageError compareImages(const Image& image, const Image& ref) {
    constexpr int B = 4;
    double sumR[3] = {0, 0, 0}, sumI[3] = {0, 0, 0}, sq[3] = {0, 0, 0}, blockSq[3] = {0, 0, 0};
    int n = 0, blocks = 0;
    for (int by = 0; by < ref.height / B; ++by)
        for (int bx = 0; bx < ref.width / B; ++bx) {
            double blockI[3] = {0, 0, 0}, blockR[3] = {0, 0, 0};
            bool covered = true;
            for (int y = by * B; y < (by + 1) * B; ++y)
                for (int x = bx * B; x < (bx + 1) * B; ++x) {
                    const float* r = ref.pixel(x, y);
                    const float* v = image.pixel(x, y);
                    covered &= r[3] >= 0.5f;
                    if (r[3] < 0.5f) continue;
                    for (int c = 0; c < 3; ++c) {
                        sumR[c] += r[c];
                        sumI[c] += v[c];
                        sq[c] += (v[c] - r[c]) * (v[c] - r[c]);
                        blockR[c] += r[c];
                        blockI[c] += v[c];
                    }
                    ++n;
                }
            if (!covered) continue;
            for (int c = 0; c < 3; ++c) {
                double d = (blockI[c] - blockR[c]) / (B * B);
                blockSq[c] += d * d;
            }
            ++blocks;
        }
    ImageError e{0, 0, 0, {0, 0, 0}, 0};
    const double totalR = sumR[0] + sumR[1] + sumR[2], totalI = sumI[0] + sumI[1] + sumI[2];
    for (int c = 0; c < 3; ++c) {
        const double mean = sumR[c] / n;
        e.relRmse = std::max(e.relRmse, std::sqrt(sq[c] / n) / mean);
        e.blockRmse = std::max(e.blockRmse, std::sqrt(blockSq[c] / blocks) / mean);
        e.channelBias[c] = (sumI[c] - sumR[c]) / sumR[c];
        if (std::abs(e.channelBias[c]) > std::abs(e.bias)) e.bias = e.channelBias[c];
        e.chromaticity = std::max(e.chromaticity, std::abs(sumI[c] / totalI - sumR[c] / totalR));
    }
    return e;
}

Image renderToExr(const std::string& scene, const std::string& out, const std::string& args) {
    std::string log;
    const int status =
        runMirage("render '" + scene + "' -o '" + out + "' --threads 2 --quiet " + args, &log);
    EXPECT_EQ(status, 0) << log;
    return status == 0 ? readExr(out) : Image();
}

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
    const std::string path = dir + "/" + name;
    std::ofstream(path) << text;
    return path;
}

double channelMean(const Image& im, int c) {
    double sum = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) sum += im.pixel(x, y)[c];
    return sum / (double(im.width) * im.height);
}

}  // namespace mirage::test
