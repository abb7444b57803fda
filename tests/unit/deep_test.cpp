// Deep output (film/deep.h, docs/aovs.md "Deep EXR"): flattening the deep image gives the
// beauty, and an opaque card put into the deep samples at a known depth gives what a render
// with that card in the scene gives in front of it.
#include "film/deep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "film/color.h"
#include "frame/render_frame.h"
#include "render/camera.h"
#include "scene/scene.h"
#include "test_support.h"
#include "tools/asset_writer.h"

using namespace mirage;

namespace {

// Fire and a fog ball over a floor (scene "mixed"), or the fog ball alone lit from behind the
// camera, with an opaque black card through its centre or not ("fog", "card").
Scene loadDeepScene(const std::string& integrator, const std::string& kind, int spp) {
    const std::string dir = test::tempDir();
    if (!std::filesystem::exists(dir + "/fog.vdb")) {
        writeProceduralAsset("fire", dir + "/fire.vdb", 16, 3);
        writeProceduralAsset("fog-sphere", dir + "/fog.vdb", 16, 1);
    }
    const std::string path = dir + "/deep_" + integrator + kind + ".toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [24, 16]\nspp = " << spp << "\nseed = 7\n"
      << "[render]\nintegrator = \"" << integrator << "\"\nphotons = 20000\n"
      << "[camera]\nposition = [0.0, 0.5, 4.0]\nlook_at = [0.0, 0.5, 0.0]\nfov = 30.0\n"
      << "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 4.0\n"
      << "transform = { scale = 0.5, translate = [0.3, 0.0, 0.0] }\n"
      << "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = 0.6\n"
      << "[[material]]\nname = \"black\"\ntype = \"diffuse\"\nreflectance = 0.0\n";
    if (kind == "mixed")
        f << "[[volume]]\nfile = \"fire.vdb\"\nshader = \"fire\"\ndensity_scale = 6.0\n"
             "transform = { scale = 0.6, translate = [-0.5, 0.0, 0.0] }\n"
             "[[shape]]\ntype = \"quad\"\ncorner = [-3, 0, 3]\nedge_u = [6, 0, 0]\n"
             "edge_v = [0, 0, -6]\nmaterial = \"white\"\n"
             "[[light]]\ntype = \"distant\"\ndirection = [-0.5, -1, -0.3]\n";
    else
        f << "[[light]]\ntype = \"distant\"\ndirection = [0.0, 0.0, -1.0]\n";
    if (kind == "card")
        f << "[[shape]]\ntype = \"quad\"\ncorner = [-3, -2, 0]\nedge_u = [6, 0, 0]\n"
             "edge_v = [0, 5, 0]\nmaterial = \"black\"\n";
    f.close();
    ColorPipeline color;
    Scene scene = loadScene(path, {}, color);
    scene.settings.progress = Progress::Mode::Quiet;
    scene.photon.progress = Progress::Mode::Quiet;
    scene.settings.deep.path = dir + "/deep.exr";
    return scene;
}

// Front-to-back over of a pixel's samples (they are sorted by Z).
void flatten(const std::vector<DeepPoint>& points, double rgba[4]) {
    double T = 1;
    for (int c = 0; c < 4; ++c) rgba[c] = 0;
    for (const DeepPoint& p : points) {
        for (int c = 0; c < 4; ++c) rgba[c] += T * p.rgba[c];
        T *= 1.0 - p.rgba[3];
    }
}

}  // namespace

TEST(Deep, FlatteningGivesTheBeauty) {
    ColorPipeline color;
    for (const char* integrator : {"single", "volpath", "photon"}) {
        Scene scene = loadDeepScene(integrator, "mixed", 8);
        RenderedFrame frame = renderFrame(scene, color);
        ASSERT_TRUE(frame.deep) << integrator;
        // Through the file (float), as a compositor reads it.
        const std::string path = test::tempDir() + "/deep_" + integrator + ".exr";
        writeDeepExr(path, *frame.deep, false, color.workingSpace(), {});
        const DeepFilm deep = readDeepExr(path);
        const Image& beauty = frame.image;
        size_t maxSamples = 0;
        for (int y = 0; y < beauty.height; ++y)
            for (int x = 0; x < beauty.width; ++x) {
                const std::vector<DeepPoint>& points = deep.pixel(x, y);
                maxSamples = std::max(maxSamples, points.size());
                for (size_t i = 1; i < points.size(); ++i)
                    EXPECT_LE(points[i - 1].zBack, points[i].z + 1e-6f) << integrator;
                double flat[4];
                flatten(points, flat);
                const float* b = beauty.pixel(x, y);
                for (int c = 0; c < 4; ++c)
                    EXPECT_NEAR(flat[c], b[c], 1e-3 * std::abs(b[c]) + 1e-6)
                        << integrator << " pixel " << x << "," << y << " channel " << c;
            }
        // Tens of samples, not thousands (alpha and colour tolerances 0.02).
        EXPECT_GT(maxSamples, 2u) << integrator;
        EXPECT_LT(maxSamples, 120u) << integrator;
    }
}

TEST(Deep, AnOpaqueCardInsertedAtItsDepthMatchesARenderWithTheCard) {
    ColorPipeline color;
    Scene fog = loadDeepScene("single", "fog", 64);
    Scene card = loadDeepScene("single", "card", 64);
    card.settings.deep.path.clear();
    const RenderedFrame open = renderFrame(fog, color);
    const RenderedFrame closed = renderFrame(card, color);
    const PerspectiveCamera camera(fog.render.camera, fog.settings.width, fog.settings.height);
    double deepSum[3] = {0, 0, 0}, cardSum[3] = {0, 0, 0};
    int pixels = 0;
    for (int y = 0; y < fog.settings.height; ++y)
        for (int x = 0; x < fog.settings.width; ++x) {
            // The card (plane z = 0) along the pixel's central ray.
            const Ray r = camera.generate(float(x) + 0.5f, float(y) + 0.5f);
            const float d = -r.o.z / r.d.z;
            double front[4] = {0, 0, 0, 0}, T = 1;
            for (const DeepPoint& p : open.deep->pixel(x, y)) {
                if (p.z >= d) break;
                DeepPoint q = p;
                if (p.zBack > d) {
                    // The part of a volumetric sample in front of d (Beer–Lambert within it).
                    const double f = (d - p.z) / (p.zBack - p.z);
                    const double a = 1.0 - std::pow(1.0 - std::min(double(p.rgba[3]), 0.999999), f);
                    // A sample of no opacity (light scattered where the walk's coverage rounds
                    // to 0): its colour spread evenly, the limit of a / alpha as alpha → 0.
                    const double share = p.rgba[3] > 0.f ? a / p.rgba[3] : f;
                    for (int c = 0; c < 3; ++c) q.rgba[c] = float(p.rgba[c] * share);
                    q.rgba[3] = float(a);
                }
                for (int c = 0; c < 4; ++c) front[c] += T * q.rgba[c];
                T *= 1.0 - q.rgba[3];
            }
            // Black card behind: it adds no colour and makes the pixel opaque.
            const float* b = closed.image.pixel(x, y);
            EXPECT_EQ(b[3], 1.f);
            if (front[3] < 0.05) continue;
            ++pixels;
            for (int c = 0; c < 3; ++c) {
                deepSum[c] += front[c];
                cardSum[c] += b[c];
            }
        }
    ASSERT_GT(pixels, 20);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(deepSum[c] / cardSum[c], 1.0, 0.05) << c;
}
