// `mirage tradeoff`: the CSV has a row per setting and a column per varied key, error falls as
// samples rise, a rendered reference is written and can be passed back, and mistakes on the
// command line give one clear message and exit 1. A 24×24 fog sphere keeps each run short.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "film/image_io.h"
#include "frame/render_frame.h"
#include "scene/scene.h"
#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

// A small scene: the procedural fog sphere with the smoke shader, lit by a sun, 24×24 pixels.
std::string writeScene(const std::string& dir) {
    test::makeFogSphere(dir);
    std::ofstream f(dir + "/scene.toml");
    f << "[film]\nresolution = [24, 24]\nspp = 4\nseed = 3\n"
         "[render]\nintegrator = \"volpath\"\n"
         "[camera]\nposition = [0, 1, 4]\nlook_at = [0, 1, 0]\nfov = 35\n"
         "[[volume]]\nfile = \"fog.vdb\"\nshader = \"smoke\"\ndensity_scale = 3\n"
         "[[light]]\ntype = \"sun\"\ndirection = [0.6, -0.7, -0.4]\nirradiance = 1476\n";
    return dir + "/scene.toml";
}

std::vector<std::vector<std::string>> readCsv(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        rows.push_back(cells);
    }
    return rows;
}

TEST(Tradeoff, ErrorFallsWithSamplesAndTheReferenceIsWrittenAndReused) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir), prefix = dir + "/a_";
    std::string out;
    ASSERT_EQ(test::runMirage("tradeoff '" + scene + "' --vary spp=1,16 -o '" + prefix + "'", &out),
              0)
        << out;
    EXPECT_NE(out.find("reference: volpath, 256 spp"), std::string::npos) << out;
    ASSERT_TRUE(fs::exists(prefix + "reference.exr"));
    ASSERT_TRUE(fs::exists(prefix + "tradeoff.png"));
    EXPECT_GT(fs::file_size(prefix + "tradeoff.png"), 1000u);

    auto rows = readCsv(prefix + "tradeoff.csv");
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows[0], (std::vector<std::string>{"setting", "seconds", "rmse", "relmse",
                                                 "mean_bias", "spp", "grid_bytes"}));
    EXPECT_EQ(rows[1][0], "spp=1");
    EXPECT_EQ(rows[2][0], "spp=16");
    EXPECT_EQ(rows[2][5], "16");
    for (int r = 1; r <= 2; ++r) ASSERT_EQ(rows[r].size(), 7u);
    const double rmse1 = std::stod(rows[1][2]), rmse16 = std::stod(rows[2][2]);
    EXPECT_GT(rmse1, 0.0);
    EXPECT_LT(rmse16, rmse1);
    EXPECT_LT(std::stod(rows[2][3]), std::stod(rows[1][3]));  // relMSE too

    // The written reference, passed back: no new reference, the same errors (same seeds).
    const std::string prefix2 = dir + "/b_";
    ASSERT_EQ(test::runMirage("tradeoff '" + scene + "' --vary spp=1,16 --reference '" + prefix +
                                  "reference.exr' -o '" + prefix2 + "'",
                              &out),
              0)
        << out;
    EXPECT_EQ(out.find("reference: volpath"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(prefix2 + "reference.exr"));
    auto again = readCsv(prefix2 + "tradeoff.csv");
    ASSERT_EQ(again.size(), 3u);
    EXPECT_EQ(again[1][2], rows[1][2]);
    EXPECT_EQ(again[2][2], rows[2][2]);

    // Two keys form the Cartesian product: 2 × 2 rows, one column per key.
    const std::string prefix3 = dir + "/c_";
    ASSERT_EQ(test::runMirage("tradeoff '" + scene + "' --vary spp=1,2 --vary integrator=single,"
                              "volpath --reference '" + prefix + "reference.exr' -o '" + prefix3 +
                                  "'",
                              &out),
              0)
        << out;
    auto product = readCsv(prefix3 + "tradeoff.csv");
    ASSERT_EQ(product.size(), 5u);
    EXPECT_EQ(product[0].size(), 8u);
    EXPECT_EQ(product[0][6], "integrator");
    EXPECT_EQ(product[2][0], "spp=1 integrator=volpath");
    EXPECT_EQ(product[4][5], "2");
    EXPECT_EQ(product[4][6], "volpath");
}

TEST(Tradeoff, BadInputGivesOneClearMessage) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    struct Case {
        std::string args, message;
    };
    const std::vector<Case> cases = {
        {"--vary foo=1,2", "unknown key 'foo'"},
        {"--vary spp=", "empty list of values"},
        {"--vary spp=1,,4", "empty value"},
        {"--vary spp=1,x", "'x' is not a number"},
        {"--vary photons=1.5", "is not a whole number"},
        {"--vary estimate=beam,cone", "expected beam or point"},
        {"--vary spp", "expected NAME=v1,v2"},
    };
    for (const auto& c : cases) {
        std::string out;
        EXPECT_EQ(test::runMirage("tradeoff '" + scene + "' " + c.args + " -o '" + dir + "/x_'",
                                  &out),
                  1)
            << c.args << ": " << out;
        EXPECT_NE(out.find("mirage: error:"), std::string::npos) << out;
        EXPECT_NE(out.find(c.message), std::string::npos) << c.args << ": " << out;
    }

    // A reference of another resolution is refused before any render.
    std::string out;
    ASSERT_EQ(test::runMirage("render '" + scene + "' --resolution 16x16 --spp 1 -q -o '" + dir +
                                  "/small.exr'",
                              &out),
              0)
        << out;
    EXPECT_EQ(test::runMirage("tradeoff '" + scene + "' --vary spp=1,2 --reference '" + dir +
                                  "/small.exr' -o '" + dir + "/y_'",
                              &out),
              1);
    EXPECT_NE(out.find("the reference is 16x16 but the renders are 24x24"), std::string::npos)
        << out;
}

// The photon mapper's knobs: photons × estimate, against the volpath reference. Each estimate
// has its column, the photon count too, and for beam and point alike more photons means less
// error (the density estimate's variance falls; at 24×24 and 4 spp the bias is below it).
TEST(Tradeoff, PhotonCountAndEstimateSweepWithThePhotonIntegrator) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir), prefix = dir + "/p_";
    std::string out;
    ASSERT_EQ(test::runMirage("tradeoff '" + scene + "' --set render.integrator=photon "
                                  "--vary photons=300,30000 --vary estimate=beam,point -o '" +
                                  prefix + "'",
                              &out),
              0)
        << out;
    auto rows = readCsv(prefix + "tradeoff.csv");
    ASSERT_EQ(rows.size(), 5u) << out;
    ASSERT_EQ(rows[0].size(), 8u);
    EXPECT_EQ(rows[0][5], "photons");
    EXPECT_EQ(rows[0][6], "estimate");
    std::map<std::string, double> rmse;
    for (size_t r = 1; r < rows.size(); ++r) {
        ASSERT_EQ(rows[r].size(), 8u);
        rmse[rows[r][6] + "/" + rows[r][5]] = std::stod(rows[r][2]);
    }
    for (const char* estimate : {"beam", "point"}) {
        const std::string e(estimate);
        ASSERT_TRUE(rmse.count(e + "/300") && rmse.count(e + "/30000")) << out;
        EXPECT_LT(rmse[e + "/30000"], rmse[e + "/300"]) << e;
    }
}

// `render --quality`: the presets raise the samples from draft to final, scaling what the scene
// states; an explicit --spp or --set film.spp wins over the preset.
TEST(Tradeoff, QualityPresetsSetSamplesUnlessOverridden) {
    const std::string dir = test::tempDir();
    const std::string scene = writeScene(dir);
    auto sppOf = [&](const std::string& args) {
        std::string out;
        const std::string exr = dir + "/q.exr";
        EXPECT_EQ(test::runMirage("render '" + scene + "' --resolution 4x4 -q -o '" + exr + "' " +
                                      args,
                                  &out),
                  0)
            << args << ": " << out;
        std::map<std::string, std::string> meta;
        readExr(exr, &meta);
        return std::stoi(meta["mirage:spp"]);
    };
    const int draft = sppOf("--quality draft"), preview = sppOf("--quality preview"),
              finalSpp = sppOf("--quality final");
    EXPECT_LT(draft, preview);
    EXPECT_LT(preview, finalSpp);
    // The scene states spp = 4, what it needs: the presets scale it by 1/4, 1 and 4.
    EXPECT_EQ(draft, 1);
    EXPECT_EQ(preview, 4);
    EXPECT_EQ(finalSpp, 16);
    EXPECT_EQ(sppOf("--quality final --spp 3"), 3);
    EXPECT_EQ(sppOf("--quality final --set film.spp=5"), 5);
    // With the photon integrator the presets set the photon count too (the EXR records the
    // photons traced), unless render.photons is given.
    auto photonsOf = [&](const std::string& args) {
        std::string log;
        const std::string exr = dir + "/ph.exr";
        EXPECT_EQ(test::runMirage("render '" + scene + "' --integrator photon --resolution 4x4 "
                                      "--spp 1 -q -o '" + exr + "' " + args,
                                  &log),
                  0)
            << args << ": " << log;
        std::map<std::string, std::string> meta;
        readExr(exr, &meta);
        return std::stoll(meta["mirage:photons_traced"]);
    };
    EXPECT_EQ(photonsOf("--quality draft"), 100000);
    EXPECT_EQ(photonsOf("--quality draft --set render.photons=2000"), 2000);

    std::string out;
    // A command-line error exits 2 (docs/cli.md), with the option named.
    const int code =
        test::runMirage("render '" + scene + "' --quality best -o '" + dir + "/x.exr'", &out);
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("--quality"), std::string::npos) << out;
}

}  // namespace
}  // namespace mirage
