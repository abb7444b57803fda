// Velocity motion blur against its known answer. A puff moving at a constant velocity V is, at
// time offset Δt, the still puff translated by V·Δt, so a blurred render must equal the mean of
// still renders of the puff translated to times spread over the shutter. The blur length is
// V × shutter width / fps: an fps taken as 24 instead of the scene's makes the blur 12 times
// shorter and fails the comparison. Dozens of renders per integrator (minutes under the
// sanitizers), so they live with the physics tests; tests/unit/motion_blur_test.cpp has the
// rest of motion blur's tests.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "puff_scene.h"
#include "test_support.h"

namespace mirage {
namespace {

using namespace puff;

void expectBlurIsMeanOfTranslatedStills(const std::string& integrator) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    constexpr int kReps = 8;
    std::vector<std::vector<double>> blurred;
    for (int r = 0; r < kReps; ++r) {
        Rendered b =
            renderScene(writeScene(dir, "blur", kOpen, ""), 1000 + uint64_t(r), integrator);
        EXPECT_EQ(b.stats.aboveMajorant, 0u);
        EXPECT_GT(b.stats.mediumLookups, 0u);
        blurred.push_back(b.Y);
    }
    const Estimate blur = combine(blurred);
    // Blur length = speed × shutter (frames) / fps: 1 m, ±0.5 m about the frame.
    const double half = 0.5 * kSpeed * kShutter / kFps;
    const Estimate stills = stillComposite(dir, half, kReps, 5000, integrator);
    const double z = worstColumnZ(blur, stills, 48, 24);
    std::printf("%s: worst band %.2f sigma from the translated stills\n", integrator.c_str(), z);
    EXPECT_LT(z, 4.0);
    // The same stills spread over the blur an fps of 24 would give: clearly not the render.
    const Estimate wrongFps =
        stillComposite(dir, 0.5 * kSpeed * kShutter / 24.0, kReps, 9000, integrator, 4);
    const double zWrong = worstColumnZ(blur, wrongFps, 48, 24);
    std::printf("%s: the stills of an fps of 24 %.1f sigma from the blurred render\n",
                integrator.c_str(), zWrong);
    EXPECT_GT(zWrong, 10.0);
}

TEST(MotionBlur, BlurredPuffIsTheMeanOfTranslatedStillsSingleScatter) {
    // Delta tracking to the scattering event along the camera ray, ratio-tracked shadow rays.
    expectBlurIsMeanOfTranslatedStills("single");
}

TEST(MotionBlur, BlurredPuffIsTheMeanOfTranslatedStillsVolpath) {
    expectBlurIsMeanOfTranslatedStills("volpath");
}

}  // namespace
}  // namespace mirage
