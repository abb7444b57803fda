// `mirage render --integrator photon` reports its two passes: the summary line and the EXR
// header carry photons traced and stored, photon-pass seconds and rate, map and disc-BVH build
// times and the estimate time (docs/cli.md, "mirage render"). A 16×16 fog sphere keeps it short.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include "film/image_io.h"
#include "test_support.h"

namespace mirage {
namespace {

std::string writeFogScene(const std::string& dir) {
    test::makeFogSphere(dir);
    std::ofstream f(dir + "/scene.toml");
    f << "[film]\nresolution = [16, 16]\nspp = 2\nseed = 1\n"
         "[render]\nintegrator = \"photon\"\nphotons = 20000\nestimate = \"beam\"\n"
         "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 35\n"
         "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3\n"
         "[[light]]\ntype = \"sun\"\ndirection = [0.6, -0.7, -0.4]\nirradiance = 1476\n";
    return dir + "/scene.toml";
}

TEST(PhotonSummary, RenderWritesPhotonFiguresToTheSummaryAndTheExrHeader) {
    const std::string dir = test::tempDir();
    const std::string scene = writeFogScene(dir), exr = dir + "/out.exr";
    std::string out;
    ASSERT_EQ(test::runMirage("render '" + scene + "' -o '" + exr + "' --threads 2", &out), 0)
        << out;
    for (const char* words : {"20000 traced", "photon pass", "photons/s", "photon map build",
                              "disc BVH build", "beam estimate"})
        EXPECT_NE(out.find(words), std::string::npos) << words << "\n" << out;

    std::map<std::string, std::string> meta;
    readExr(exr, &meta);
    auto value = [&](const std::string& key) {
        auto it = meta.find("mirage:" + key);
        EXPECT_NE(it, meta.end()) << "mirage:" << key << " missing";
        return it == meta.end() ? -1.0 : std::stod(it->second);
    };
    EXPECT_EQ(meta["mirage:photons_traced"], "20000");
    for (const char* key : {"photons_stored", "photon_pass_seconds", "photons_per_second",
                            "photon_map_build_seconds", "photon_radii_seconds",
                            "disc_bvh_build_seconds", "estimate_seconds"})
        EXPECT_GT(value(key), 0.0) << key;
    // The rate is the count over the pass time, as printed.
    EXPECT_NEAR(value("photons_per_second") * value("photon_pass_seconds"), 20000.0, 20.0);
}

TEST(PhotonSummary, OtherIntegratorsWriteNoPhotonFigures) {
    const std::string dir = test::tempDir();
    const std::string scene = writeFogScene(dir), exr = dir + "/out.exr";
    std::string out;
    ASSERT_EQ(test::runMirage("render '" + scene + "' -o '" + exr + "' --integrator single", &out),
              0)
        << out;
    std::map<std::string, std::string> meta;
    readExr(exr, &meta);
    EXPECT_EQ(meta.count("mirage:photons_traced"), 0u);
    EXPECT_EQ(out.find("photons:"), std::string::npos) << out;
}

}  // namespace
}  // namespace mirage
