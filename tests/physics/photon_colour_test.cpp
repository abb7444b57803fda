// The photon part sees colour as the camera path does. A photon estimate sums photons at their
// own wavelengths, so whatever the camera path puts in front of the photons — a tinted mirror,
// a coloured medium before a mirror, earlier chords of a curved camera ray — must weigh each
// photon at its wavelength (photon/view_weight.h). Grey stand-ins (a mean over the path's four
// wavelengths, or 550 nm) pass grey scenes and fail these, each by far more than the tolerance:
//  - a red mirror reflecting photon-lit fog: the photon integrator against volpath, per channel;
//  - the same fog seen through a red-absorbing box by a white mirror, likewise;
//  - a red-absorbing box in front of the fog seen by camera rays that curve (a vanishing index
//    gradient) against straight ones, the photon integrator both times, per channel;
//  - the fog seen through a dispersive glass ball, where the chain follows the hero wavelength
//    alone: the photon integrator against volpath, per channel;
//  - a fluorescent dye seen through that ball: volpath's inelastic event against the photons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// A dense, nearly white fog sphere (multiple scattering carries most of its light), lit by a
// sun from the side, parallel to the mirrors of the tests below: volpath cannot sample light
// a mirror reflects from a delta light (no NEE through a mirror), the photons can, and the
// two would differ by that caustic. Shaders for the fog and for a red filter.
std::string writeCommon(const std::string& dir) {
    test::makeFogSphere(dir);
    std::ofstream(dir + "/white_fog.toml") << "name = \"white_fog\"\n[[component]]\n"
                                               "grid = \"density\"\nsigma_a = 0.05\n"
                                               "sigma_s = 4.0\n";
    std::ofstream(dir + "/red_filter.toml") << "name = \"red_filter\"\n[[component]]\n"
                                                "sigma_a = [0.05, 3.0, 3.0]\n";
    return "[[volume]]\nfile = \"fog.vdb\"\nshader = \"white_fog.toml\"\n"
           "[[light]]\ntype = \"sun\"\ndirection = [-0.8, -0.6, 0]\nirradiance = 1000\n";
}

Image render(const std::string& dir, const std::string& name, const std::string& text,
             const std::string& args) {
    const std::string scene = dir + "/" + name + ".toml";
    std::ofstream(scene) << text;
    std::string log;
    EXPECT_EQ(test::runMirage("render '" + scene + "' -o '" + dir + "/" + name +
                                  ".exr' --quiet --threads 2 " + args,
                              &log),
              0)
        << log;
    return readExr(dir + "/" + name + ".exr");
}

// Each channel's mean within `tolerance` of the reference's, relative to that channel or, for
// a channel far darker than the brightest (a red image's blue), to a quarter of the brightest:
// a colour error is judged against the light the pixel has.
void expectSameColour(const Image& a, const Image& ref, const double (&tolerance)[3]) {
    double brightest = 0;
    for (int c = 0; c < 3; ++c) brightest = std::max(brightest, test::channelMean(ref, c));
    ASSERT_GT(brightest, 1e-4) << "the reference is black";
    for (int c = 0; c < 3; ++c) {
        const double x = test::channelMean(a, c), r = test::channelMean(ref, c);
        std::printf("channel %d: %.5f against %.5f (ratio %.3f)\n", c, x, r, x / r);
        EXPECT_NEAR(x, r, tolerance[c] * std::max(r, 0.25 * brightest)) << "channel " << c;
    }
}
void expectSameColour(const Image& a, const Image& ref, double tolerance) {
    expectSameColour(a, ref, {tolerance, tolerance, tolerance});
}

const char* kPhoton = "--integrator photon --set render.photons=1000000 --spp 16";
const char* kVolpath = "--integrator volpath --spp 512";

TEST(PhotonColour, RedMirrorReflectsRedFog) {
    const std::string dir = test::tempDir();
    const std::string scene =
        writeCommon(dir) +
        "[film]\nresolution = [12, 12]\nseed = 2\n"
        "[camera]\nposition = [0, 1, -3]\nlook_at = [0, 1, -6]\nfov = 30\n"
        "[[material]]\nname = \"red_mirror\"\ntype = \"mirror\"\nreflectance = [0.9, 0.05, 0.05]\n"
        "[[shape]]\ntype = \"quad\"\ncorner = [-3, -2, -6]\nedge_u = [6, 0, 0]\n"
        "edge_v = [0, 6, 0]\nmaterial = \"red_mirror\"\n";
    const Image photon = render(dir, "photon", scene, kPhoton);
    const Image volpath = render(dir, "volpath", scene, kVolpath);
    expectSameColour(photon, volpath, 0.12);
}

TEST(PhotonColour, RedFilterBeforeAWhiteMirror) {
    const std::string dir = test::tempDir();
    const std::string scene =
        writeCommon(dir) +
        "[film]\nresolution = [12, 12]\nseed = 3\n"
        "[camera]\nposition = [0, 1, -3]\nlook_at = [0, 1, -6]\nfov = 30\n"
        "[[volume]]\nbox = { min = [-2, -1, -4.5], max = [2, 3, -4.0] }\n"
        "shader = \"red_filter.toml\"\n"
        "[[material]]\nname = \"mirror\"\ntype = \"mirror\"\n"
        "[[shape]]\ntype = \"quad\"\ncorner = [-3, -2, -6]\nedge_u = [6, 0, 0]\n"
        "edge_v = [0, 6, 0]\nmaterial = \"mirror\"\n";
    const Image photon = render(dir, "photon", scene, kPhoton);
    const Image volpath = render(dir, "volpath", scene, kVolpath);
    // The red the filter passes is held to 12 % (550 nm attenuation made it 34 % dark). Green
    // and blue, a fifth and a seventh of red, come out 11 % and 22 % above volpath with this
    // fix and without it alike, at 10⁶ or 4·10⁶ photons and k = 8 or 16: a difference outside
    // the view weight, held here to 30 % and left open.
    expectSameColour(photon, volpath, {0.12, 0.3, 0.3});
}

TEST(PhotonColour, CurvedCameraRaysAttenuatePhotonsAtTheirWavelength) {
    const std::string dir = test::tempDir();
    const std::string scene =
        writeCommon(dir) +
        "[film]\nresolution = [12, 12]\nseed = 4\n"
        "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 34\n"
        "[[volume]]\nbox = { min = [-2, -1, 2.0], max = [2, 3, 2.5] }\n"
        "shader = \"red_filter.toml\"\n";
    const Image straight = render(dir, "straight", scene, kPhoton);
    const Image curved = render(dir, "curved",
                                scene + "[refraction]\nprofile = \"linear\"\nk = 1e-9\n"
                                        "max_distance = 20\nmax_step = 0.5\n",
                                kPhoton);
    expectSameColour(curved, straight, 0.08);
}

TEST(PhotonColour, DispersiveBallKeepsTheHeroWavelengthsLight) {
    const std::string dir = test::tempDir();
    const std::string scene =
        writeCommon(dir) +
        "[film]\nresolution = [12, 12]\nseed = 5\n"
        "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 24\n"
        "[[material]]\nname = \"flint\"\ntype = \"dielectric\"\nior = 1.6\ncauchy_b = 0.05\n"
        "[[shape]]\ntype = \"sphere\"\ncenter = [0, 1, 2.2]\nradius = 0.7\nmaterial = \"flint\"\n";
    const Image photon = render(dir, "photon", scene, kPhoton);
    const Image volpath = render(dir, "volpath", scene, kVolpath);
    expectSameColour(photon, volpath, 0.12);
}

// A dye that absorbs only below 550 nm (Γ = 0.5) and glows around 630 nm, seen through a
// dispersive ball: behind it the camera path carries its hero wavelength alone, so volpath's
// red paths meet a dye with σa(λo) = 0. Choosing re-emission as a branch of absorption (∝ σa
// at the path's wavelengths) never re-emitted on them and lost the red glow; the inelastic
// event of its own finds it, as the photon map does.
TEST(PhotonColour, FluorescentDyeBehindDispersiveGlass) {
    const std::string dir = test::tempDir();
    std::ofstream(dir + "/dye.toml")
        << "name = \"dye\"\n[[component]]\n"
           "sigma_a = { wavelengths = [360, 545, 555, 830], values = [3.0, 3.0, 0.0, 0.0] }\n"
           "sigma_s = 0.3\nquantum_efficiency = 0.5\nemission_peak_nm = 630\n"
           "emission_fwhm_nm = 30\n";
    const std::string scene =
        "[film]\nresolution = [12, 12]\nseed = 6\n"
        "[camera]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\nfov = 24\n"
        "[[volume]]\nbox = { min = [-1, -1, -1], max = [1, 1, 1] }\nshader = \"dye.toml\"\n"
        "[[light]]\ntype = \"sun\"\ndirection = [-0.8, -0.6, 0]\nirradiance = 1000\n"
        "[[material]]\nname = \"flint\"\ntype = \"dielectric\"\nior = 1.6\ncauchy_b = 0.02\n"
        "[[shape]]\ntype = \"sphere\"\ncenter = [0, 0, 2.2]\nradius = 0.7\n"
        "material = \"flint\"\n";
    // Both estimates of this glow are noisy (the re-emitted light passes the ball on the hero
    // wavelength alone): at kPhoton and kVolpath their green means moved ~9 % from seed to
    // seed, each, so a 15 % tolerance failed about one seed in four. With 4× the photons and
    // 8× the samples, ~3 % each (seeds 6-8: photons 0.0271-0.0287, volpath 0.0273-0.0287).
    const Image photon =
        render(dir, "photon", scene, "--integrator photon --set render.photons=4000000 --spp 16");
    const Image volpath = render(dir, "volpath", scene, "--integrator volpath --spp 4096");
    expectSameColour(volpath, photon, 0.15);
}

}  // namespace
}  // namespace mirage
