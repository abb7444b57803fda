// The underwater pair (assets/scenes/underwater.toml and underwater_green.toml, after Gutierrez
// et al. 2005, figure 6: the same scene at 0.1 and 2 mg/m³ of chlorophyll) shows what it is
// there for, measured on reduced renders of the shipped scene files: the higher concentration
// is greener (chlorophyll absorbs blue) and hazier (its particles scatter: the sand floor in the
// bottom rows no longer stands out from the water in the top rows).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "test_support.h"

namespace mirage {
namespace {

// Mean scene-linear G and B over rows [y0, y1).
struct GreenBlue {
    double g = 0, b = 0;
};
GreenBlue meanOfRows(const Image& im, int y0, int y1) {
    GreenBlue m;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < im.width; ++x) {
            m.g += im.pixel(x, y)[1];
            m.b += im.pixel(x, y)[2];
        }
    const double n = double(im.width) * (y1 - y0);
    m.g /= n;
    m.b /= n;
    return m;
}

TEST(UnderwaterPair, HigherChlorophyllIsGreenerAndHazier) {
    const std::string dir = test::tempDir();
    auto renderScene = [&](const std::string& name) {
        const std::string scene =
            test::shippedSceneCopy(dir, name + ".toml", "ocean", "ocean_plume.vdb", 32);
        return test::renderToExr(scene, dir + "/" + name + ".exr", "--resolution 32x18 --spp 64");
    };
    const Image low = renderScene("underwater"), high = renderScene("underwater_green");
    ASSERT_EQ(low.height, 18);
    const GreenBlue lowAll = meanOfRows(low, 0, 18), highAll = meanOfRows(high, 0, 18);
    // Haze: how far the floor (bottom 4 rows) stands out from the open water (top 4), in stops.
    auto contrast = [](const Image& im) {
        return std::abs(std::log2(meanOfRows(im, 14, 18).g / meanOfRows(im, 0, 4).g));
    };
    std::printf(
        "underwater G/B: 0.1 mg/m³ %.3f, 2 mg/m³ %.3f; floor against water: %.2f and "
        "%.2f stops\n",
        lowAll.g / lowAll.b, highAll.g / highAll.b, contrast(low), contrast(high));
    // Measured here: G/B 0.54 and 1.07; 2.4 and 0.6 stops (at 48 × 27: 2.2 and 0.2).
    EXPECT_GT(highAll.g / highAll.b, 1.5 * lowAll.g / lowAll.b);
    EXPECT_LT(contrast(high), 0.5 * contrast(low));
}

}  // namespace
}  // namespace mirage
