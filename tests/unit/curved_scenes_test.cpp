// The curved-light scenes shipped in assets/scenes/ load and render without ../shared (their
// procedural caches made by `mirage make-asset` next to a copy of the scene), and the flattened
// sun sits where the astronomers' refraction on the round Earth puts it (Bennett 1982).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/math.h"
#include "film/image_io.h"
#include "refraction_tables.h"
#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

// Copies the scene into a fresh folder (with the cache it needs, if any) and returns the copy.
std::string sceneCopy(const std::string& name, const std::string& asset = "",
                      const std::string& file = "") {
    return test::shippedSceneCopy(test::tempDir(), name, asset, file);
}

TEST(CurvedScenes, EachRendersWithoutSharedData) {
    struct Case {
        const char* scene;
        const char* asset;
        const char* file;
    };
    for (const Case& c :
         {Case{"inferior_mirage.toml", "", ""}, Case{"superior_mirage.toml", "", ""},
          Case{"fata_morgana.toml", "", ""},
          Case{"heat_haze.toml", "fire", "fire_haze.vdb"},
          Case{"flattened_sun.toml", "fog-sphere", "fog_sphere.vdb"}}) {
        const std::string scene = sceneCopy(c.scene, c.asset, c.file);
        std::string out;
        ASSERT_EQ(test::runMirage("info '" + scene + "'", &out), 0) << out;
        EXPECT_NE(out.find("Camera rays bend"), std::string::npos) << c.scene << out;
        ASSERT_EQ(test::runMirage("render '" + scene + "' -o '" + scene +
                                      ".exr' --resolution 24x12 --spp 1 --threads 2 --quiet",
                                  &out),
                  0)
            << c.scene << out;
        EXPECT_TRUE(fs::exists(scene + ".exr")) << c.scene;
    }
}

TEST(CurvedScenes, FlattenedSunSitsWhereTheRefractionTablesPutIt) {
    const std::string scene = sceneCopy("flattened_sun.toml", "fog-sphere", "fog_sphere.vdb");
    // 150×100 pixels over 3° × 2° (0.02° each; rows from +1.9° down), the fog off.
    std::string log;
    ASSERT_EQ(test::runMirage("render '" + scene + "' -o '" + scene +
                                  ".exr' --resolution 150x100 --spp 2 --threads 2 --quiet "
                                  "--set volume.0.density_scale=0",
                              &log),
              0)
        << log;
    const Image im = readExr(scene + ".exr");
    int top = im.height, bottom = -1, left = im.width, right = -1;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            if (im.pixel(x, y)[0] > 4.f) {  // the sun's red is 8, the sky's 0.25
                top = std::min(top, y);
                bottom = std::max(bottom, y);
                left = std::min(left, x);
                right = std::max(right, x);
            }
    ASSERT_GE(bottom, top) << "no sun in the frame";
    const double degPerPixel = 2.0 / im.height;
    const double seenTop = 1.9 - top * degPerPixel, seenBottom = 1.9 - (bottom + 1) * degPerPixel;
    const double seenWidth = (right + 1 - left) * degPerPixel;
    // The prediction: the sun's limbs at 0.5° ± 0.265° outside the air, seen through Bennett's
    // refraction (0.685° and 1.152°).
    const double predictedTop = test::apparentAltitude(0.765),
                 predictedBottom = test::apparentAltitude(0.235);
    std::printf("sun seen %.3f°–%.3f° (Bennett: %.3f°–%.3f°), %.3f° wide\n", seenBottom, seenTop,
                predictedBottom, predictedTop, seenWidth);
    // Within two pixels (the sun is 1e8 m away: its parallax from the paths' 20–40 km height at
    // 700 km is ~0.01°; Bennett's formula and the standard atmosphere differ by < 1′ here).
    EXPECT_NEAR(seenTop, predictedTop, 2 * degPerPixel);
    EXPECT_NEAR(seenBottom, predictedBottom, 2 * degPerPixel);
    EXPECT_NEAR(seenWidth, 0.53, 2 * degPerPixel);
    // Straight, it would be 0.53° tall at 0.235°–0.765°: here it is lifted and flattened, its
    // vertical diameter ~0.88 of its horizontal.
    EXPECT_NEAR((seenTop - seenBottom) / seenWidth, (predictedTop - predictedBottom) / 0.53,
                4 * degPerPixel / 0.53);
}

}  // namespace
}  // namespace mirage
