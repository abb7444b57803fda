// Camera and volume motion within the shutter ([[camera.key]], turntables,
// [[volume.transform.key]], the curved camera of [refraction]): known answers.
//
// A path has one time, so a blurred render is the time average of the still renders over the
// shutter. A camera panning over a still puff, a turntable turning, a puff carried by its keyed
// transform: each blurred render must equal the mean of stills at N times spread over the
// shutter (within 4σ per band of columns), and differ clearly from the still at the frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "puff_scene.h"
#include "test_support.h"

namespace mirage {
namespace {

using namespace puff;

constexpr int kReps = 8;

std::string cameraAt(double x) {
    char b[160];
    std::snprintf(b, sizeof b, "position = [%.9g, 0, 4]\nlook_at = [%.9g, 0, 0]\nfov = 25\n", x, x);
    return b;
}

// Replicate blurred renders of `blurred` and the mean of stills stillAt(u), compared.
void expectBlurIsMeanOfStills(const std::string& blurred,
                              const std::function<std::string(double)>& stillAt,
                              const std::string& stillAtFrame, const std::string& integrator) {
    std::vector<std::vector<double>> reps;
    for (int r = 0; r < kReps; ++r) {
        Rendered b = renderScene(blurred, 1000 + uint64_t(r), integrator);
        EXPECT_EQ(b.stats.aboveMajorant, 0u);
        reps.push_back(b.Y);
    }
    const Estimate blur = combine(reps);
    const double z = worstColumnZ(blur, meanOfStills(stillAt, kReps, 5000, integrator), 48, 24);
    std::printf("%s: worst band %.2f sigma from the stills over the shutter\n", integrator.c_str(),
                z);
    EXPECT_LT(z, 4.0);
    // The still at the frame alone is clearly not the blurred render.
    const Estimate still =
        meanOfStills([&](double) { return stillAtFrame; }, kReps, 9000, integrator, 1);
    const double zStill = worstColumnZ(blur, still, 48, 24);
    std::printf("%s: the still at the frame %.1f sigma from the blurred render\n",
                integrator.c_str(), zStill);
    EXPECT_GT(zStill, 10.0);
}

TEST(CameraMotionBlur, PanningCameraIsTheMeanOfStills) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    PuffScene blur = stillPuff(kOpen);
    blur.camera = "fov = 25\n";
    blur.cameraKeys = kPanKeys;
    PuffScene still = stillPuff();
    expectBlurIsMeanOfStills(
        writePuffScene(dir, "pan", blur),
        [&](double u) {
            still.camera = cameraAt(u * kHalfPan);
            return writePuffScene(dir, "still", still);
        },
        writeScene(dir, "frame", "", kStill), "single");
}

TEST(CameraMotionBlur, TurntableBlursAlongItsOrbit) {
    // 16 frames per turn: ±0.5 frame is ±11.25° about the look-at point 2 m in front of the
    // camera, the puff 2 m beyond it, so the puff sweeps across the image.
    const std::string dir = test::tempDir();
    writePuff(dir);
    auto orbit = [](double degrees) {
        const double a = degrees * 3.14159265358979323846 / 180.0;
        char b[160];
        std::snprintf(b, sizeof b, "position = [%.9g, 0, %.9g]\nlook_at = [0, 0, 2]\nfov = 25\n",
                      2.0 * std::sin(a), 2.0 + 2.0 * std::cos(a));
        return std::string(b);
    };
    PuffScene blur = stillPuff(kOpen);
    blur.camera = "position = [0, 0, 4]\nlook_at = [0, 0, 2]\nfov = 25\nturntable = 16\n";
    PuffScene still = stillPuff();
    auto stillAt = [&](double degrees) {
        still.camera = orbit(degrees);
        return writePuffScene(dir, "still", still);
    };
    expectBlurIsMeanOfStills(
        writePuffScene(dir, "turntable", blur), [&](double u) { return stillAt(u * 11.25); },
        stillAt(0.0), "single");
}

TEST(VolumeMotionBlur, KeyedTranslationIsTheMeanOfTranslatedStills) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    PuffScene blur = stillPuff(kOpen);
    blur.transformKeys = kTranslateKeys;
    for (const char* integrator : {"single", "volpath"}) {
        SCOPED_TRACE(integrator);
        expectBlurIsMeanOfStills(
            writePuffScene(dir, "carried", blur),
            [&](double u) { return writeScene(dir, "still", "", kStill, u * kHalfPan); },
            writeScene(dir, "frame", "", kStill), integrator);
    }
}

TEST(CurvedCameraBlur, BentCameraRaysSeeTheMovingPuffAtTheirTime) {
    // The puff moving by its velocity grid, seen through a vertical index gradient (camera rays
    // bend, by ~1 mm over the scene): the blurred render through the curved camera is the mean
    // of the curved-camera stills of the translated puff.
    const std::string dir = test::tempDir();
    writePuff(dir);
    const std::string refraction = "[refraction]\nprofile = \"linear\"\nn0 = 1.0\nk = 1e-3\n";
    PuffScene blur;
    blur.shutter = kOpen;
    blur.extra = refraction;
    PuffScene still = stillPuff();
    still.extra = refraction;
    auto stillAt = [&](double dx) {
        still.dx = dx;
        return writePuffScene(dir, "still", still);
    };
    expectBlurIsMeanOfStills(
        writePuffScene(dir, "curved", blur),
        [&](double u) { return stillAt(u * 0.5 * kSpeed * kShutter / kFps); }, stillAt(0.0),
        "single");
}

}  // namespace
}  // namespace mirage
