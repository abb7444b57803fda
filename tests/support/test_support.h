// Helpers shared by the test programs: where the reference data is, temporary folders,
// running the mirage binary.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace mirage::test {

// ../shared/data, or "" when absent (tests that need it call GTEST_SKIP with a message).
std::string sharedData();
std::string sharedFile(const std::string& relative);  // "" when missing
// A fresh folder under the system temp dir, unique per test.
std::string tempDir();
// Runs `mirage <args>` (the built binary), returns its exit code; stdout+stderr into *output.
int runMirage(const std::string& args, std::string* output = nullptr);
// Runs `mirage render SCENE -q --threads 2 ARGS -o EXR`, expecting exit code 0 (else a test
// failure with its output), and returns the EXR's metadata.
std::map<std::string, std::string> renderMetadata(const std::string& scene, const std::string& args,
                                                  const std::string& exr);
// Runs a shell command, returns its exit code; stdout+stderr into *output.
int runCommand(const std::string& cmd, std::string* output = nullptr);
// The built mirage binary and the source tree. Only test_support.cpp is compiled with these
// absolute paths, so every other translation unit is the same in any checkout (and a compiler
// cache serves it to a second working tree).
std::string mirageBinary();
std::string sourceDir();

// Writes the procedural fog sphere (`mirage make-asset fog-sphere --resolution R`) to
// DIR/fog.vdb and returns that path; a failure is a test failure.
std::string makeFogSphere(const std::string& dir, int resolution = 16);
// DIR/scene.toml: the fog sphere of makeFogSphere(dir) with the smoke shader (density_scale 3)
// under a sun, or under the [[light]] whose body `light` is, seen from (0, 1, 4); `film` and
// `render` are the bodies of its [film] and [render] tables (TOML lines). Returns the scene's
// path.
std::string writeFogSphereScene(const std::string& dir, const std::string& film,
                                const std::string& render, const std::string& light = "");
// DIR/sunny.hdr, a sky map with a sun (Light::lobe): 32 × 16 pixels of 0.2 and one of 300 at
// row 4 (45° up), in flat RGBE scanlines. Returns its path.
std::string writeSunnySky(const std::string& dir);

// A scene shipped in assets/scenes/ of the source tree.
std::string shippedScene(const std::string& name);
// Copies that scene into `dir` and, where it names a procedural cache, writes the cache beside
// it with `mirage make-asset ASSET -o DIR/FILE --resolution R` (as the scene's header says,
// smaller); returns the copy's path. Failures are test failures.
std::string shippedSceneCopy(const std::string& dir, const std::string& name,
                             const std::string& asset = "", const std::string& file = "",
                             int resolution = 16);

}  // namespace mirage::test

#define MIRAGE_REQUIRE_SHARED(var, rel)                                               \
    std::string var = ::mirage::test::sharedFile(rel);                                \
    if (var.empty()) GTEST_SKIP() << "reference data ../shared/data/" << (rel)        \
                                  << " is absent; skipping"

#include <array>
#include <functional>

#include "film/film.h"
#include "light/dome_light.h"
#include "medium/medium.h"
#include "render/renderer.h"
#include "volume/grid_lookup.h"

namespace mirage::test {

// A NanoVDB fog-volume grid built in memory: value(i, j, k) over the inclusive index box
// [lo, hi]³, voxel size h (m), index (0,0,0) at `origin`. Zero values stay inactive.
FloatGrid makeGrid(const std::function<float(int, int, int)>& value, int lo, int hi, double h,
                   const Vec3d& origin = Vec3d(0.0), const std::string& name = "density");


// A ShaderDesc of one grey component reading grid slot "density" (σ in 1/m per unit
// density, HG asymmetry g).
ShaderDesc greyShader(float sigmaA, float sigmaS, float g = 0.f);
// greyShader() emitting as a blackbody at grid slot "temperature" (a fire's smoke).
ShaderDesc glowingShader(float sigmaA, float sigmaS, float g = 0.f);

// A medium of greyShader() over makeGrid(value, lo, hi, h): the test scenes' workhorse.
std::unique_ptr<Medium> gridMedium(const std::function<float(int, int, int)>& value, int lo,
                                   int hi, double h, float sigmaA, float sigmaS, float g = 0.f,
                                   const Transform& objectToWorld = Transform());

// ∫ σt along the segment a → b (σt = sigmaT × the grid's value), by the midpoint rule over 2000
// steps on the grid's own trilinear field: the closed forms the estimators are checked against.
double opticalDepth(const FloatGrid& g, const Vec3& a, const Vec3& b, double sigmaT);

// A scene of one medium: a 2 m cube of unit density about the origin (voxels of 1/8 m, faces
// fading over half a voxel), gridMedium(1, σa 0, σs sigmaS, HG g); no light.
RenderScene unitCubeScene(float sigmaS, float g);

// A lat-long sky map of width × height pixels, every one `value` in each channel.
LatLongImage flatSky(int width, int height, float value);

// ∫ e^−τ(0, t) f(ray(t)) dt over [t0, t1] (τ = sigmaT × the grid's value along the ray), in the
// angle θ the ray subtends at a point `D` from it nearest at t = `nearest` (t = nearest +
// D tan θ, 8000 steps): the single scattering of a lamp's peak by quadrature, smooth where its
// 1/d² is not; f is σs ρ p times the light arriving at the point.
double quadratureAlongRay(const FloatGrid& g, const Ray& ray, double t0, double t1, double nearest,
                          double D, double sigmaT, const std::function<double(const Vec3&)>& f);

// The numbers of path i of an estimate averaged over paths 0, 1, …: with Sobol, the paths are
// the samples of one pixel (one low-discrepancy sequence); with random, independent streams.
inline Sampler pathSampler(SamplerKind kind, uint64_t seed, uint64_t i) {
    return kind == SamplerKind::Sobol ? Sampler(kind, seed, 0, i) : Sampler(seed, i, 0);
}
constexpr SamplerKind kSamplerKinds[] = {SamplerKind::Sobol, SamplerKind::Random};

// Small test renders: width × height pixels in 8-pixel tiles, quiet.
RenderSettings smallRenderSettings(int spp, uint64_t seed, int width = 32, int height = 32);

// A 1 m box of heterogeneous smoke (σa 0.5, σs 4 per unit density, g 0.3) under a sun, seen
// whole with a margin of background: every pixel's value depends on its samples.
RenderScene sunlitSmokeBox();
// Whether two films hold the same bits: sums, squared sums, alpha and sample counts.
bool sameFilm(const Film& a, const Film& b);

// The mean, its standard error and the largest of `samples` estimates L[0] of one ray by an
// integrator, each path with its own random stream and wavelengths: the known-answer checks of
// an estimator against quadrature along a ray.
struct RayEstimate {
    double mean, se, largest;
};
RayEstimate estimateAlongRay(const Integrator& integrator, const RenderScene& scene,
                             const Ray& ray, int samples);
// Prints `what`: the expected value, each estimate and its largest sample against its mean,
// and checks both means against `expected` within 4 standard errors and 1 %: an estimator with
// its lamp sampling (equiangular) and without.
void expectBothNear(const char* what, double expected, const RayEstimate& equiangular,
                    const RayEstimate& distance);
// The same for each of the path's wavelengths, L[0] … L[3] (the hero and its rotations): the
// checks of a spectral estimator per channel.
std::array<RayEstimate, kSpectrumSamples> estimateAlongRayPerWavelength(
    const Integrator& integrator, const RenderScene& scene, const Ray& ray, int samples);

// volpath filmed at four wavelengths per sample (the integrator's radiance declared not
// light-shaped), as before the exact-colour shortcuts of render/achromatic_film.h.
class SpectralFilmVolpath : public Integrator {
public:
    const IntegratorInfo& info() const override { return mInner->info(); }
    RadianceSample Li(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                      Sampler& sampler, ThreadState& ts) const override {
        return mInner->Li(scene, ray, w, sampler, ts);
    }

private:
    std::unique_ptr<Integrator> mInner = makeVolPathIntegrator();
};

// An image against a reference over the pixels the reference covers (alpha ≥ 0.5: background
// and fringes excluded), in scene-linear RGB, each channel on its own relative to that
// channel's mean in the reference: an error in one colour is not diluted by the other two (a
// sum over channels would pass a red image with the right brightness for a grey reference).
struct ImageError {
    // The worst channel of each measure.
    double relRmse = 0;    // √(mean (I_c − R_c)²) / mean R_c over the covered pixels
    double blockRmse = 0;  // the same on the means of 4×4-pixel blocks wholly covered
    double bias = 0;       // (mean I_c − mean R_c) / mean R_c, the channel of largest magnitude
    double channelBias[3] = {0, 0, 0};
    // The largest |c_I − c_R| of the mean chromaticities c = (R, G, B) / (R + G + B): a shift
    // of colour at the same brightness.
    double chromaticity = 0;
};
ImageError compareImages(const Image& image, const Image& ref);

// Renders a scene file to `out` (an EXR) quietly on two threads with extra `args`, and reads it
// back; a failed render is a test failure (and an empty image).
Image renderToExr(const std::string& scene, const std::string& out, const std::string& args);

// Writes `text` to DIR/NAME (a scene file) and returns that path.
std::string writeFile(const std::string& dir, const std::string& name, const std::string& text);

// The mean of channel c (0 = R, 1 = G, 2 = B) over every pixel of an image.
double channelMean(const Image& im, int c);

// The mean of Monte Carlo samples and its standard error, for a furnace-style check
// (|mean − answer| within a few standard errors).
struct SampleMean {
    double sum = 0, sum2 = 0;
    int n = 0;
    void add(double x) {
        sum += x;
        sum2 += x * x;
        ++n;
    }
    double mean() const { return n > 0 ? sum / n : 0.0; }
    double standardError() const {
        return n > 0 ? std::sqrt(std::max(0.0, sum2 / n - mean() * mean()) / n) : 0.0;
    }
};

}  // namespace mirage::test
