// Holdouts (docs/aovs.md, "Holdouts"): a holdout shape is black with zero alpha inside its
// silhouette, in every pass, while the fog in front of it keeps its light and coverage; a
// holdout volume adds no light and no coverage of its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "film/color.h"
#include "frame/render_frame.h"
#include "scene/scene.h"
#include "test_support.h"
#include "tools/asset_writer.h"

using namespace mirage;

namespace {

// A fog ball (centre (0, 0.5, 0), radius 0.5) above a floor (ending in front of the card unless
// longFloor), lit
// from behind the camera, and a black card (no light of its own to bounce) behind the ball's
// left half: `card` is "" (none), "holdout" or "opaque".
Image render(const std::string& integrator, const std::string& card, bool fogHoldout = false,
             bool longFloor = false) {
    const std::string dir = test::tempDir();
    if (!std::filesystem::exists(dir + "/fog.vdb"))
        writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    const std::string path = dir + "/holdout_" + integrator + card + (fogHoldout ? "_fog" : "") +
                             (longFloor ? "_long" : "") + ".toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [24, 16]\nspp = 16\nseed = 5\n"
         "[render]\nintegrator = \""
      << integrator
      << "\"\n"
         "[camera]\nposition = [0.0, 0.6, 4.0]\nlook_at = [0.0, 0.5, 0.0]\nfov = 30.0\n"
         "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 2.0\n"
         "transform = { scale = 0.5, translate = [0.0, 0.0, 0.0] }\n"
      << (fogHoldout ? "holdout = true\n" : "")
      << "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = 0.6\n"
         "[[material]]\nname = \"black\"\ntype = \"diffuse\"\nreflectance = 0.0\n"
         "[[shape]]\ntype = \"quad\"\ncorner = [-3, 0, 3]\nedge_u = [6, 0, 0]\n"
         "edge_v = [0, 0, "
      << (longFloor ? -6.0 : -3.6) << "]\nmaterial = \"white\"\n";
    if (!card.empty())
        f << "[[shape]]\ntype = \"quad\"\ncorner = [-1.4, 0.1, -0.7]\nedge_u = [1.4, 0, 0]\n"
             "edge_v = [0, 1.0, 0]\nmaterial = \"black\"\nholdout = "
          << (card == "holdout" ? "true" : "false") << "\n";
    f << "[[light]]\ntype = \"distant\"\ndirection = [0.2, -0.4, -1.0]\ngroup = \"key\"\n"
         "[output]\naovs = [\"volume_direct\", \"surface_direct\", \"lightgroup_key\", "
         "\"lightgroup_emission\"]\n";
    f.close();
    ColorPipeline color;
    Scene scene = loadScene(path, {}, color);
    scene.settings.progress = Progress::Mode::Quiet;
    return renderFrame(scene, color).image;
}

// Every channel of the beauty and of every pass at pixel p.
double largestValue(const Image& image, size_t p) {
    double m = 0;
    for (int c = 0; c < 4; ++c) m = std::max(m, double(std::abs(image.rgba[p * 4 + c])));
    for (const ImageLayer& l : image.layers)
        for (size_t c = 0; c < l.channels.size(); ++c)
            m = std::max(m, double(std::abs(l.pixels[p * l.channels.size() + c])));
    return m;
}

}  // namespace

TEST(Holdout, ShapeIsBlackWithZeroAlphaInsideItsSilhouette) {
    for (const char* integrator : {"single", "volpath"}) {
        const Image none = render(integrator, ""), held = render(integrator, "holdout"),
                    opaque = render(integrator, "opaque");
        int clear = 0, fogged = 0;
        double alphaNone = 0, alphaHeld = 0, redNone = 0, redHeld = 0;
        for (size_t p = 0; p < size_t(none.width) * none.height; ++p) {
            const bool card = opaque.rgba[p * 4 + 3] == 1.f && none.rgba[p * 4 + 3] < 1.f;
            if (!card) continue;
            if (none.rgba[p * 4 + 3] == 0.f) {
                // Nothing in front of the card: black, transparent, in every pass.
                ++clear;
                EXPECT_EQ(largestValue(held, p), 0.0) << integrator << " pixel " << p;
            } else if (none.rgba[p * 4 + 3] > 0.2f) {
                // Fog in front of the card: its light and coverage as without the card.
                ++fogged;
                alphaNone += none.rgba[p * 4 + 3];
                alphaHeld += held.rgba[p * 4 + 3];
                redNone += none.rgba[p * 4];
                redHeld += held.rgba[p * 4];
            }
        }
        EXPECT_GT(clear, 5) << integrator;
        ASSERT_GT(fogged, 5) << integrator;
        EXPECT_NEAR(alphaHeld / alphaNone, 1.0, 0.08) << integrator;
        EXPECT_NEAR(redHeld / redNone, 1.0, 0.12) << integrator;
    }
}

TEST(Holdout, VolumeAddsNoLightAndNoCoverage) {
    for (const char* integrator : {"single", "volpath"}) {
        const Image fog = render(integrator, "", false, true),
                    held = render(integrator, "", true, true);
        int sky = 0, floor = 0;
        for (size_t p = 0; p < size_t(fog.width) * fog.height; ++p) {
            const float a = fog.rgba[p * 4 + 3];
            // The upper rows look up, past the floor's end: the fog there is against the sky.
            const bool up = p < size_t(fog.width) * size_t(fog.height / 2);
            if (up && a > 0.1f && a < 1.f) {
                // Fog against the sky: the holdout fog is black and (nearly) transparent.
                ++sky;
                EXPECT_EQ(held.rgba[p * 4], 0.f) << integrator << " pixel " << p;
                EXPECT_LT(std::abs(held.rgba[p * 4 + 3]), 0.05f) << integrator << " pixel " << p;
            } else if (a == 1.f && held.rgba[p * 4 + 3] < 0.95f) {
                // The floor seen through the holdout fog: covered only where the fog lets
                // it be seen, and dimmed by it.
                ++floor;
                EXPECT_GT(held.rgba[p * 4 + 3], 0.f) << integrator << " pixel " << p;
            }
        }
        EXPECT_GT(sky, 5) << integrator;
        EXPECT_GT(floor, 5) << integrator;
    }
}
