// Helpers shared by the test programs: where the reference data is, temporary folders,
// running the mirage binary.
#pragma once

#include <string>

// OpenVDB allocates whatever size a corrupt Blosc chunk claims (up to terabytes): a normal build
// gets std::bad_alloc, which Mirage reports as one message, but the operator new of
// AddressSanitizer and of ThreadSanitizer aborts on such a request instead of throwing. Tests
// feeding corrupt payloads skip those cases in a sanitizer build (pipeline/sanitize.sh); the
// normal build runs them.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define MIRAGE_TEST_ABORTING_NEW 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define MIRAGE_TEST_ABORTING_NEW 1
#endif
#endif

namespace mirage::test {

#ifdef MIRAGE_TEST_ABORTING_NEW
constexpr bool kSanitizerAllocator = true;
#else
constexpr bool kSanitizerAllocator = false;
#endif

// ../shared/data, or "" when absent (tests that need it call GTEST_SKIP with a message).
std::string sharedData();
std::string sharedFile(const std::string& relative);  // "" when missing
// A fresh folder under the system temp dir, unique per test.
std::string tempDir();
// Runs `mirage <args>` (the built binary), returns its exit code; stdout+stderr into *output.
int runMirage(const std::string& args, std::string* output = nullptr);
// Runs a shell command, returns its exit code; stdout+stderr into *output.
int runCommand(const std::string& cmd, std::string* output = nullptr);

}  // namespace mirage::test

#define MIRAGE_REQUIRE_SHARED(var, rel)                                               \
    std::string var = ::mirage::test::sharedFile(rel);                                \
    if (var.empty()) GTEST_SKIP() << "reference data ../shared/data/" << (rel)        \
                                  << " is absent; skipping"

#include <functional>

#include "film/film.h"
#include "medium/medium.h"
#include "render/renderer.h"
#include "volume/grid.h"

namespace mirage::test {

// A NanoVDB fog-volume grid built in memory: value(i, j, k) over the inclusive index box
// [lo, hi]³, voxel size h (m), index (0,0,0) at `origin`. Zero values stay inactive.
FloatGrid makeGrid(const std::function<float(int, int, int)>& value, int lo, int hi, double h,
                   const Vec3d& origin = Vec3d(0.0), const std::string& name = "density");


// A ShaderDesc of one grey component reading grid slot "density" (σ in 1/m per unit
// density, HG asymmetry g).
ShaderDesc greyShader(float sigmaA, float sigmaS, float g = 0.f);

// A medium of greyShader() over makeGrid(value, lo, hi, h): the test scenes' workhorse.
std::unique_ptr<Medium> gridMedium(const std::function<float(int, int, int)>& value, int lo,
                                   int hi, double h, float sigmaA, float sigmaS, float g = 0.f,
                                   const Transform& objectToWorld = Transform());

// Small test renders: width × height pixels in 8-pixel tiles, quiet.
RenderSettings smallRenderSettings(int spp, uint64_t seed, int width = 32, int height = 32);

// An image against a reference over the pixels the reference covers (alpha ≥ 0.5: background
// and fringes excluded), in scene-linear RGB, relative to the reference's mean.
struct ImageError {
    double relRmse;    // √(mean (I − R)²) / mean R over the covered pixels and channels
    double blockRmse;  // the same on the means of 4×4-pixel blocks wholly covered
    double bias;       // (mean I − mean R) / mean R over the covered pixels
};
ImageError compareImages(const Image& image, const Image& ref);

}  // namespace mirage::test
