// Photons from sphere lights and IES profiles carry the light that next-event estimation sees:
// a fog sphere lit by a coloured sphere light beside it, and by a small sphere above it shaped
// by the asymmetric IES profile of tests/ies/headlight.ies aimed down at it, rendered by the photon
// integrator and by volpath, compared per channel. The fog is nearly white and dense enough that
// multiple scattering (the photons' share) is most of its light, so a photon emitted from the wrong
// place, in the wrong direction or with the wrong weight shows as a difference in brightness or
// colour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

const char* kPhoton = "--integrator photon --set render.photons=500000 --spp 16";
const char* kVolpath = "--integrator volpath --spp 128";

std::string fog(const std::string& dir) {
    test::makeFogSphere(dir);
    std::ofstream(dir + "/white_fog.toml") << "name = \"white_fog\"\n[[component]]\n"
                                              "grid = \"density\"\nsigma_a = 0.05\n"
                                              "sigma_s = 4.0\n";
    return "[[volume]]\nfile = \"fog.vdb\"\nshader = \"white_fog.toml\"\n"
           "[film]\nresolution = [12, 12]\nseed = 7\n"
           "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 34\n";
}

// Both renders of `scene`, each channel's mean of the photon image within `tolerance` of
// volpath's.
void expectSameColour(const std::string& dir, const std::string& scene, double tolerance) {
    const std::string file = test::writeFile(dir, "scene.toml", scene);
    const Image photon = test::renderToExr(file, dir + "/photon.exr", kPhoton);
    const Image volpath = test::renderToExr(file, dir + "/volpath.exr", kVolpath);
    const test::ImageError e = test::compareImages(photon, volpath);
    for (int c = 0; c < 3; ++c) {
        std::printf("channel %d: photon/volpath − 1 = %+.3f\n", c, e.channelBias[c]);
        EXPECT_LT(std::abs(e.channelBias[c]), tolerance) << "channel " << c;
        EXPECT_GT(test::channelMean(volpath, c), 1e-4) << "channel " << c << " is black";
    }
}

}  // namespace

TEST(LampPhotons, SphereLightMatchesVolpathPerChannel) {
    const std::string dir = test::tempDir();
    const std::string scene = fog(dir) +
                              "[[light]]\ntype = \"point\"\nposition = [1.6, 1.6, 0.4]\n"
                              "radius = 0.4\npower = 300\ncolor = [1.0, 0.55, 0.25]\n";
    expectSameColour(dir, scene, 0.08);
}

TEST(LampPhotons, IesSphereDownlightMatchesVolpathPerChannel) {
    const std::string dir = test::tempDir();
    const std::string scene = fog(dir) + "[[light]]\ntype = \"point\"\nposition = [0.3, 2.5, 0]\n" +
                              "radius = 0.1\npower = 300\ncolor = [0.3, 0.6, 1.0]\nies = \"" +
                              test::sourceDir() + "/tests/ies/headlight.ies\"\n" +
                              "direction = [-0.2, -1, 0.1]\n";
    expectSameColour(dir, scene, 0.08);
}

}  // namespace mirage
