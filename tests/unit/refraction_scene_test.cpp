// The [refraction] scene key: a field with ∇n = 0 (or none) leaves the render bit-identical, and
// an inferior mirage shows: over a road 60 K hotter near the ground, camera rays aimed slightly
// down at the road turn up and see a bright wall 400 m away, where straight rays see the dark
// road.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// A black road (y = 0), a bright emissive wall facing the camera at x = 400 m, a camera 1.5 m
// up looking 0.3° down with a 1° field of view, 32×16 pixels.
std::string mirageScene(const std::string& dir, const std::string& refraction) {
    const std::string path = dir + "/road.toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [32, 16]\nspp = 2\nseed = 5\n"
         "[render]\nintegrator = \"single\"\n"
         "[camera]\nposition = [0, 1.5, 0]\nlook_at = [400, -0.594, 0]\nfov = 1\n"
         "[[light]]\ntype = \"sun\"\ndirection = [0.3, -1, 0.2]\nirradiance = 1\n"
         "[[material]]\nname = \"road\"\ntype = \"diffuse\"\nreflectance = 0.0\n"
         "[[material]]\nname = \"wall\"\ntype = \"diffuse\"\nreflectance = 0.0\nemission = 1.0\n"
         "[[shape]]\ntype = \"quad\"\ncorner = [-10, 0, 100]\nedge_u = [1000, 0, 0]\n"
         "edge_v = [0, 0, -200]\nmaterial = \"road\"\n"
         "[[shape]]\ntype = \"quad\"\ncorner = [400, 0, -100]\nedge_u = [0, 0, 200]\n"
         "edge_v = [0, 10, 0]\nmaterial = \"wall\"\n"
      << refraction << "[output]\npath = \"road.exr\"\nhalf = false\n";
    return path;
}

const char* kHotRoad =
    "[refraction]\nprofile = \"atmosphere\"\nmax_step = 2.0\nmax_distance = 1000.0\n"
    "[[refraction.inversion]]\nbase = -2.0\ntop = 0.5\ndelta_t = 60.0\nblend = 1.0\n";

Image render(const std::string& scene, const std::string& out) {
    return test::renderToExr(scene, out, "");
}

// Mean of channel c (R by default) over rows [y0, y1).
double rowsMean(const Image& im, int y0, int y1, int c = 0) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < im.width; ++x) sum += im.pixel(x, y)[c];
    return sum / (double(y1 - y0) * im.width);
}

TEST(RefractionScene, NoGradientRendersBitIdentically) {
    const std::string dir = test::tempDir();
    const Image plain = render(mirageScene(dir, ""), dir + "/plain.exr");
    const Image flat = render(mirageScene(dir, "[refraction]\nprofile = \"linear\"\nn0 = 1.0003\n"),
                              dir + "/flat.exr");
    ASSERT_EQ(plain.width, flat.width);
    ASSERT_EQ(plain.rgba.size(), flat.rgba.size());
    EXPECT_TRUE(plain.rgba == flat.rgba);
    std::string info;
    ASSERT_EQ(test::runMirage("info '" + mirageScene(dir, kHotRoad) + "'", &info), 0) << info;
    EXPECT_NE(info.find("US Standard Atmosphere 1976 with 1 inversion"), std::string::npos) << info;
    EXPECT_NE(info.find("shadow rays to lights at infinity bend too"), std::string::npos) << info;
    // The cheaper approximation, by choice: camera rays alone bend.
    std::string straight = kHotRoad;
    straight.insert(straight.find("[[refraction.inversion]]"), "curved_transport = false\n");
    ASSERT_EQ(test::runMirage("info '" + mirageScene(dir, straight) + "'", &info), 0) << info;
    EXPECT_NE(info.find("curved_transport = false"), std::string::npos) << info;
}

TEST(RefractionScene, HotRoadShowsTheWallBelowTheHorizon) {
    const std::string dir = test::tempDir();
    const Image straight = render(mirageScene(dir, ""), dir + "/straight.exr");
    const Image mirage = render(mirageScene(dir, kHotRoad), dir + "/mirage.exr");
    // Rows look 0.3° ± 0.5° down (top row first): the lower half looks 0.3°–0.8° down, where a
    // straight ray from 1.5 m meets the road within 290 m.
    const double lowStraight = rowsMean(straight, 8, 16), lowMirage = rowsMean(mirage, 8, 16);
    EXPECT_LT(lowStraight, 0.05) << "the road is black";
    EXPECT_GT(lowMirage, 0.2) << "the wall's image in the road";
    // The top rows see the wall directly in both.
    EXPECT_GT(rowsMean(straight, 0, 2), 0.5);
    EXPECT_GT(rowsMean(mirage, 0, 2), 0.5);
}

TEST(RefractionScene, FireTemperatureGridBendsOnlyNearTheFire) {
    // Heat haze: the fire cache's temperature grid → n (Stam & Languenou), seen against a wall
    // of emissive stripes. Rays that stay clear of the grid's bricks run as one straight chord
    // and see what the straight render sees; rays through the plume may differ.
    const std::string dir = test::tempDir();
    std::string log;
    ASSERT_EQ(test::runMirage("make-asset fire -o '" + dir + "/fire.vdb' --resolution 32", &log),
              0)
        << log;
    auto scene = [&](const std::string& name, const std::string& extra) {
        std::ofstream f(dir + "/" + name);
        f << "[film]\nresolution = [48, 32]\nspp = 4\nseed = 2\n"
             "[render]\nintegrator = \"single\"\n"
             "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 40\n"
             "[[volume]]\nfile = \"fire.vdb\"\nshader = \"fire\"\n"
             "[[material]]\nname = \"glow\"\ntype = \"diffuse\"\nreflectance = 0.0\n"
             "emission = 1.0\n";
        for (int i = 0; i < 8; ++i)
            f << "[[shape]]\ntype = \"quad\"\ncorner = [" << -3 + 0.8 * i
              << ", -1, -2]\nedge_u = [0.4, 0, 0]\nedge_v = [0, 4, 0]\nmaterial = \"glow\"\n";
        f << extra;
        return dir + "/" + name;
    };
    const std::string haze = scene("haze.toml", "[refraction]\nprofile = \"grid\"\nvolume = 0\n");
    std::string info;
    ASSERT_EQ(test::runMirage("info '" + haze + "'", &info), 0) << info;
    EXPECT_NE(info.find("temperature grid 'temperature' of volume 0"), std::string::npos) << info;
    const Image straight = render(scene("plain.toml", ""), dir + "/plain.exr");
    const Image bent = render(haze, dir + "/haze.exr");
    // The outer 12 columns on each side pass the fire's plane more than 1.1 m to its side (the
    // grid's bricks reach |x| < 0.6 m): the same, up to rounding of the chord's direction.
    double outside = 0;
    for (int y = 0; y < 32; ++y)
        for (int x : {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45,
                      46, 47})
            for (int c = 0; c < 3; ++c)
                outside = std::max(outside, double(std::abs(straight.pixel(x, y)[c] -
                                                             bent.pixel(x, y)[c])));
    EXPECT_LT(outside, 1e-4);
    std::string out;
    EXPECT_EQ(test::runMirage("info '" +
                                  scene("bad.toml", "[refraction]\nprofile = \"grid\"\n"
                                                    "grid = \"heat\"\n") +
                                  "'",
                              &out),
              1);
    EXPECT_NE(out.find("no grid slot 'heat'"), std::string::npos) << out;
}

TEST(RefractionScene, BadProfileIsOneMessage) {
    const std::string dir = test::tempDir();
    std::string out;
    EXPECT_EQ(test::runMirage("info '" + mirageScene(dir, "[refraction]\nprofile = \"glass\"\n") +
                                  "'",
                              &out),
              1);
    EXPECT_NE(out.find("profile"), std::string::npos) << out;
    EXPECT_NE(out.find("linear, atmosphere or grid"), std::string::npos) << out;
}

}  // namespace
}  // namespace mirage
