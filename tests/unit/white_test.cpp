// Which white is which. A grey given as working-space RGB is neutral in the working space: an
// emitter of `emission = [a, a, a]`, seen directly, and a white diffuser lit by a light of
// `color = [1, 1, 1]` render R = G = B (ACEScg). A bare number is a spectral radiance, the
// equal-energy spectrum E, whose colour in ACEScg is warm (≈ 1.10, 0.97, 0.92 for 1 W·m⁻²·
// sr⁻¹·nm⁻¹: E's white point x = y = 1/3 against the ACES white x = 0.32168, y = 0.33767).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// Renders `body` (materials, shapes, lights) seen by a camera at the origin looking up +y at
// the plane y = 1, 32×32 pixels at 256 samples, and returns the image's mean R, G, B. The
// mean's colour noise from the sampled wavelengths is then ≤ 1e-4 (the channels' spread
// measured ≤ 9e-5 over seeds 3–5 for each scene below), a tenth of the neutrality asserted;
// 4096 samples (≤ 2e-5) took 16 times as long.
std::array<double, 3> renderMean(const std::string& dir, const std::string& name,
                                 const std::string& body) {
    const std::string scene = dir + "/" + name + ".toml";
    std::ofstream(scene) << "[film]\nresolution = [32, 32]\nspp = 256\nseed = 3\n"
                            "[render]\nintegrator = \"volpath\"\n"
                            "[camera]\nposition = [0, 0, 0]\nlook_at = [0, 10, 0]\nup = [0, 0, 1]\n"
                            "fov = 10\n"
                         << body << "[output]\npath = \"" << name << ".exr\"\nhalf = false\n";
    std::string log;
    EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + dir + "/" + name +
                                  ".exr' --threads 2 --quiet",
                              &log),
              0)
        << log;
    const Image im = readExr(dir + "/" + name + ".exr");
    std::array<double, 3> mean{0, 0, 0};
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x)
            for (int c = 0; c < 3; ++c) mean[size_t(c)] += im.pixel(x, y)[c];
    for (double& v : mean) v /= double(im.width) * im.height;
    return mean;
}

std::string emitter(const std::string& emission) {
    return "[[material]]\nname = \"lamp\"\ntype = \"diffuse\"\nreflectance = 0.0\nemission = " +
           emission +
           "\n[[shape]]\ntype = \"quad\"\ncorner = [-5, 1, -5]\nedge_u = [10, 0, 0]\n"
           "edge_v = [0, 0, 10]\nmaterial = \"lamp\"\n";
}

// max |c − mean| / mean over the channels.
double spread(const std::array<double, 3>& rgb) {
    const double mean = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
    double worst = 0;
    for (double v : rgb) worst = std::max(worst, std::abs(v - mean) / mean);
    return worst;
}

TEST(White, GreyRgbEmissionIsNeutralInTheWorkingSpace) {
    const std::string dir = test::tempDir();
    for (const char* grey : {"[1.0, 1.0, 1.0]", "[0.18, 0.18, 0.18]"}) {
        const auto rgb = renderMean(dir, "grey", emitter(grey));
        std::printf("emission = %s: R %.5f G %.5f B %.5f\n", grey, rgb[0], rgb[1], rgb[2]);
        EXPECT_LT(spread(rgb), 1e-3) << grey;
    }
}

TEST(White, WhiteDiffuserUnderAWhiteLightIsNeutral) {
    // The plane y = 1 is a white diffuser facing the camera, lit by a quad light of colour
    // [1, 1, 1] just below it, facing it (and invisible to the camera: one-sided, facing up).
    const std::string dir = test::tempDir();
    const auto rgb = renderMean(
        dir, "lit",
        "[[material]]\nname = \"white\"\ntype = \"diffuse\"\nreflectance = 1.0\n"
        "[[shape]]\ntype = \"quad\"\ncorner = [-5, 1, -5]\nedge_u = [10, 0, 0]\n"
        "edge_v = [0, 0, 10]\nmaterial = \"white\"\n"
        "[[light]]\ntype = \"quad\"\ncorner = [-2, 0.5, -2]\nedge_u = [0, 0, 4]\n"
        "edge_v = [4, 0, 0]\npower = 1000\ncolor = [1, 1, 1]\n");
    std::printf("white diffuser, white light: R %.5f G %.5f B %.5f\n", rgb[0], rgb[1], rgb[2]);
    ASSERT_GT(rgb[1], 0.0);
    EXPECT_LT(spread(rgb), 1e-3);
}

TEST(White, EqualEnergyEmissionIsWarmInAcescg) {
    // The number form: the equal-energy spectrum, as documented (docs/scene-file.md, "Which white is which").
    const auto rgb = renderMean(test::tempDir(), "e", emitter("1.0"));
    std::printf("emission = 1.0 (E): R %.4f G %.4f B %.4f\n", rgb[0], rgb[1], rgb[2]);
    EXPECT_NEAR(rgb[0], 1.104, 0.005);
    EXPECT_NEAR(rgb[1], 0.966, 0.005);
    EXPECT_NEAR(rgb[2], 0.920, 0.005);
}

}  // namespace
}  // namespace mirage
