// Every non-curved scene shipped in assets/scenes/ loads and renders without ../shared (its
// procedural cache made by `mirage make-asset` beside a copy of the scene, at a small
// resolution; in place where it reads a mesh, IES profile or shader shipped in assets/), to a
// finite, lit image; and the two scenes whose look is their point are
// checked for it: the volume caustic's beam lights the fog around the glass ball, and the
// Cornell water box turns green as chlorophyll rises (Gutierrez et al. 2005, figure 3).
// The curved-light scenes have their own test (tests/unit/curved_scenes_test.cpp), and
// smoke1_sun needs ../shared (tests/unit/smoke1_scene_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// The mean of RGB channel c over the pixel rectangle [x0, x1) × [y0, y1).
double regionMean(const Image& im, int c, int x0, int x1, int y0, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += im.pixel(x, y)[c];
    return sum / double((x1 - x0) * (y1 - y0));
}

// Renders a scene quietly on two threads into `out` (default: beside the scene, a copy), its
// preview beside it; the image, or a failed assertion.
Image render(const std::string& scene, const std::string& args, std::string out = "") {
    std::string log;
    if (out.empty()) out = scene + ".exr";
    EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + out + "' --preview '" + out +
                                  ".png' --threads 2 --quiet " + args,
                              &log),
              0)
        << log;
    return readExr(out);
}

// No pixel NaN or infinite, and the mean over the colour channels above 1e-4.
void expectFiniteAndLit(const Image& im) {
    ASSERT_GT(im.width, 0);
    double sum = 0;
    int nonFinite = 0;
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            for (int k = 0; k < 3; ++k) {
                const float v = im.pixel(x, y)[k];
                nonFinite += std::isfinite(v) ? 0 : 1;
                sum += std::isfinite(v) ? v : 0.0;
            }
    EXPECT_EQ(nonFinite, 0);
    EXPECT_GT(sum / (3.0 * im.width * im.height), 1e-4) << "a black image";
}

TEST(ShippedScenes, EachRendersFiniteAndLitWithoutSharedData) {
    struct Case {
        const char* scene;
        const char* asset;
        const char* file;
        const char* args;
    };
    const Case cases[] = {
        {"demo.toml", "plume", "demo_plume.vdb", "--resolution 24x24 --spp 2"},
        {"fog_sphere.toml", "fog-sphere", "fog_sphere.vdb",
         "--resolution 24x24 --spp 2 --set render.photons=5000"},
        {"cornell_smoke.toml", "fog-sphere", "fog_sphere.vdb",
         "--resolution 24x24 --spp 2 --set render.photons=5000"},
        {"volume_caustic.toml", "fog-sphere", "fog_sphere.vdb",
         "--resolution 24x24 --spp 2 --set render.photons=5000"},
        {"fire_smoke.toml", "fire", "fire_smoke.vdb",
         "--resolution 18x24 --spp 2 --set render.photons=5000"},
        {"cornell_water.toml", "", "", "--resolution 16x16 --spp 4"},
        {"underwater.toml", "ocean", "ocean_plume.vdb", "--resolution 24x14 --spp 4"},
        {"smoke_past_sphere.toml", "smoke-sphere", "smoke_sphere.vdb",
         "--resolution 16x20 --spp 2"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.scene);
        const std::string scene = test::shippedSceneCopy(test::tempDir(), c.scene, c.asset, c.file);
        std::string info;
        ASSERT_EQ(test::runMirage("info '" + scene + "'", &info), 0) << info;
        expectFiniteAndLit(render(scene, c.args));
    }
}

// The scenes that read a mesh, an IES profile or a shader shipped beside them in assets/
// render in place (the output in a temporary folder), as `mirage render` runs them.
TEST(ShippedScenes, ScenesWithFilesBesideThemRenderInPlace) {
    const std::string dir = test::tempDir();
    for (const char* name : {"sunken_boat", "lighthouse_fog", "headlights_fog"}) {
        SCOPED_TRACE(name);
        const std::string scene = test::shippedScene(std::string(name) + ".toml");
        expectFiniteAndLit(render(scene, "--resolution 24x16 --spp 2", dir + "/" + name + ".exr"));
    }
}

// The spot light shines down through the fog onto the ball; above the ball its beam is lit
// fog, seen against the unlit fog beside it. (With the fog confined to the ball, as an
// `interior_medium` line once made it, the beam was gone.)
TEST(ShippedScenes, VolumeCausticBeamLightsTheFogAroundTheBall) {
    const std::string scene = test::shippedSceneCopy(test::tempDir(), "volume_caustic.toml",
                                                     "fog-sphere", "fog_sphere.vdb", 32);
    const Image im = render(scene, "--resolution 64x64 --spp 8 --set render.photons=20000");
    // Camera (0, 1.3, 4.2) looking at (0, 1, 0), 40°: the beam at x = 0 between 2.0 and 2.6 m
    // up falls on the middle columns, rows ≈ 3–11; columns 8–16 there see unlit fog.
    double beam = 0, beside = 0;
    for (int c = 0; c < 3; ++c) {
        beam += regionMean(im, c, 30, 34, 3, 11);
        beside += regionMean(im, c, 8, 16, 3, 11);
    }
    EXPECT_GT(beam, 3.0 * beside) << "beam " << beam << ", beside " << beside;
    EXPECT_GT(beam, 1e-3);
}

// Figure 3 of Gutierrez et al. 2005: clear water is blue-dominated; at 5 mg/m³ chlorophyll
// absorbs blue and red, and the box turns green: G/B rises with chlorophyll. The median of the
// pixels' G/B: at 16 samples a few pixels carry a rare long path's firefly (the light sits
// inside the water), which moves a mean by tens of per cent from one seed or random-number
// layout to the next, and a median not at all.
TEST(ShippedScenes, CornellWaterTurnsGreenWithChlorophyll) {
    const std::string dir = test::tempDir();
    const std::string scene = test::shippedSceneCopy(dir, "cornell_water.toml");
    auto greenOverBlue = [&](const char* chl) {
        const Image im = render(scene, std::string("--resolution 16x16 --spp 16 "
                                                   "--set volume.0.concentration.chlorophyll=") +
                                           chl);
        std::vector<double> ratios;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                if (im.pixel(x, y)[2] > 0.f)
                    ratios.push_back(im.pixel(x, y)[1] / im.pixel(x, y)[2]);
        EXPECT_GT(ratios.size(), 128u);
        std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
        return ratios.empty() ? 0.0 : ratios[ratios.size() / 2];
    };
    const double clear = greenOverBlue("0.05"), green = greenOverBlue("5");
    EXPECT_GT(green, 1.2 * clear) << "G/B " << clear << " at 0.05 mg/m³, " << green << " at 5";
}

}  // namespace
}  // namespace mirage
