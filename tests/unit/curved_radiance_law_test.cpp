// The n² law on curved camera rays (render/curved_camera.h): L/n² is conserved along a ray, so
// radiance Le leaving a surface where the index is n2 arrives at a camera in index n1 as
// Le·(n1/n2)². The scene: a camera at y = 0 looking straight up (along ∇n, so the central rays
// do not bend and the others barely do) at an emitting ceiling at y = 1 m, in n = n0 + k·y.
// Every ray meets the ceiling where n = n0 + k, so the ratio to the render without a field is
// exact, not statistical.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

std::string ceilingScene(const std::string& dir, const std::string& name,
                         const std::string& refraction) {
    const std::string path = dir + "/" + name + ".toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [8, 8]\nspp = 1\nseed = 1\n"
         "[render]\nintegrator = \"single\"\n"
         "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 10, 0]\nup = [0, 0, 1]\nfov = 10\n"
         "[[material]]\nname = \"lamp\"\ntype = \"diffuse\"\nreflectance = 0.0\nemission = 1.0\n"
         // Facing down (edge_u × edge_v = −y), towards the camera.
         "[[shape]]\ntype = \"quad\"\ncorner = [-5, 1, -5]\nedge_u = [10, 0, 0]\n"
         "edge_v = [0, 0, 10]\nmaterial = \"lamp\"\n"
      << refraction << "[output]\npath = \"" << name << ".exr\"\nhalf = false\n";
    return path;
}

// The image's mean of each of R, G, B.
std::array<double, 3> meanRgb(const std::string& scene, const std::string& exr) {
    std::string log;
    EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + exr + "' --threads 2 --quiet", &log),
              0)
        << log;
    const Image im = readExr(exr);
    std::array<double, 3> sum{0, 0, 0};
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            for (int c = 0; c < 3; ++c) sum[size_t(c)] += im.pixel(x, y)[c];
    for (double& v : sum) v /= double(im.width) * im.height;
    return sum;
}

TEST(CurvedRadianceLaw, RadianceScalesAsTheSquareOfTheIndexRatio) {
    const std::string dir = test::tempDir();
    const auto plain = meanRgb(ceilingScene(dir, "plain", ""), dir + "/plain.exr");
    for (double v : plain) ASSERT_GT(v, 0.01);
    struct Case {
        double n0, k;  // n = n0 + k·y: n1 = n0 at the camera, n2 = n0 + k at the ceiling
    };
    for (const Case& c : {Case{1.0, 1.0}, Case{2.0, -1.0}, Case{1.0, 0.333}}) {
        const std::string name = "n" + std::to_string(int(c.n0 * 1000)) + "_" +
                                 std::to_string(int(std::lround(c.k * 1000)));
        const std::string refraction = "[refraction]\nprofile = \"linear\"\nn0 = " +
                                       std::to_string(c.n0) + "\nk = " + std::to_string(c.k) +
                                       "\n";
        const auto bent = meanRgb(ceilingScene(dir, name, refraction), dir + "/" + name + ".exr");
        const double n1 = c.n0, n2 = c.n0 + c.k;
        const double expected = (n1 / n2) * (n1 / n2);
        std::printf("n1 %.3f, n2 %.3f: radiance ratio R %.6f G %.6f B %.6f, (n1/n2)² = %.6f\n",
                    n1, n2, bent[0] / plain[0], bent[1] / plain[1], bent[2] / plain[2], expected);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(bent[size_t(ch)] / plain[size_t(ch)], expected, 1e-3 * expected)
                << name << " channel " << ch;
    }
}

}  // namespace
}  // namespace mirage
