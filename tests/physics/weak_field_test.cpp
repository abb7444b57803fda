// Curved light in a field too weak to bend anything visible (k = 1e-9/m), walked chord by chord,
// must give the image of straight light within the noise: the camera's chords add up the media
// as one straight ray does (single scattering), and curved photons carry the direct light the
// straight render takes by shadow rays (photon mapping). Statistical renders of a fog sphere,
// tens of seconds each under the sanitizers, so they live with the physics tests.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

// The fog sphere (smoke shader, density_scale 3) under the sun, with the tables of `body`
// (film, render, camera, surfaces), rendered straight and in a field of k = 1e−9/m walked in
// chords of at most maxStep metres; dir is the folder of both scenes.
struct StraightAndBent {
    Image straight, bent;
    std::string dir;
};
StraightAndBent renderStraightAndBent(const std::string& body, double maxStep) {
    StraightAndBent out;
    out.dir = test::tempDir();
    test::makeFogSphere(out.dir);
    const std::string scene =
        body +
        "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3\n"
        "[[light]]\ntype = \"sun\"\ndirection = [0.6, -0.7, -0.4]\nirradiance = 1476\n";
    const std::string field =
        "[refraction]\nprofile = \"linear\"\nk = 1e-9\nmax_distance = 20\n"
        "max_step = " +
        std::to_string(maxStep) + "\n";
    out.straight = test::renderToExr(test::writeFile(out.dir, "straight.toml", scene),
                                     out.dir + "/straight.exr", "");
    out.bent = test::renderToExr(test::writeFile(out.dir, "bent.toml", scene + field),
                                 out.dir + "/bent.exr", "");
    return out;
}

TEST(RefractionScene, ChordByChordMediaMatchTheStraightRender) {
    // A field that bends nothing visible (k = 1e−9/m) but is walked in 10 cm chords: the media
    // seen chord by chord (each chord's emission and scattering, times the transmittance of the
    // chords before) must add up to the straight render's, within the noise (≈ 0.9 % here).
    const StraightAndBent r = renderStraightAndBent(
        "[film]\nresolution = [24, 24]\nspp = 64\nseed = 11\n"
        "[render]\nintegrator = \"single\"\n"
        "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 35\n",
        0.1);
    for (int c = 0; c < 3; ++c) {
        const double a = test::channelMean(r.straight, c), b = test::channelMean(r.bent, c);
        ASSERT_GT(a, 0.01) << "channel " << c;
        EXPECT_NEAR(b / a, 1.0, 0.04) << "channel " << c;
    }
}

TEST(CurvedPhotons, WeakFieldGivesThePhotonMapImageOfStraightLight) {
    // A fog sphere under the sun above a grey floor. Straight: single scattering and direct
    // light on the floor by shadow rays, the rest from the photons. With k = 1e−9/m the photons
    // walk curved paths and carry the direct light too, which the render then takes from the
    // maps alone: the same image within the noise, nothing counted twice or missed.
    const StraightAndBent r = renderStraightAndBent(
        "[film]\nresolution = [16, 16]\nspp = 8\nseed = 4\n"
        "[render]\nintegrator = \"photon\"\nphotons = 800000\n"
        "[camera]\nposition = [0, 1.2, 4]\nlook_at = [0, 0.6, 0]\nfov = 40\n"
        "[[material]]\nname = \"floor\"\ntype = \"diffuse\"\nreflectance = 0.5\n"
        "[[shape]]\ntype = \"quad\"\ncorner = [-3, -1, 3]\nedge_u = [6, 0, 0]\n"
        "edge_v = [0, 0, -6]\nmaterial = \"floor\"\n",
        0.5);
    std::string info;
    ASSERT_EQ(test::runMirage("info '" + r.dir + "/bent.toml'", &info), 0) << info;
    EXPECT_NE(info.find("photons follow curved paths"), std::string::npos) << info;
    for (int c = 0; c < 3; ++c) {
        const double a = test::channelMean(r.straight, c), b = test::channelMean(r.bent, c);
        ASSERT_GT(a, 0.01) << c;
        std::printf("channel %d: straight %.5f, curved photons %.5f (ratio %.4f)\n", c, a, b,
                    b / a);
        EXPECT_NEAR(b / a, 1.0, 0.05) << "channel " << c;
    }
}

}  // namespace
}  // namespace mirage
