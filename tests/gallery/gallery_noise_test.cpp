// The gallery's noise check: every shipped scene (assets/scenes/*.toml) renders at its stated
// preset without visible noise — relMSE at most 10⁻² against a render with 4× the samples
// (`--quality final` scales the scene's samples and photons by 4, docs/performance.md,
// "Quality presets"), with a seed of its own so that the two renders' noise is independent.
// Both at a quarter of the scene's resolution in each dimension (the noise of a pixel does not
// depend on the pixel count; the photon pass does not shrink, so the photon scenes cost the
// most). relMSE is `mirage tradeoff`'s (the race's measure), the preset render the sweep's one
// setting, the 4× render its reference; E[relMSE] is about 1.25 × the preset's own.
//
// Label "gallery": minutes on 2 cores, so not in pipeline/test.sh's default run; run it with
// `ctest -L gallery` (docs/validation.md lists what passes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;

// The procedural caches the scenes read, made as pipeline/gallery.sh makes them.
const std::map<std::string, std::string> kCaches = {
    {"fog_sphere.vdb", "fog-sphere"},
    {"fire_smoke.vdb", "fire --resolution 96 --seed 3"},
    {"fire_haze.vdb", "fire --resolution 64 --seed 3"},
    {"ocean_plume.vdb", "ocean"},
    {"demo_plume.vdb", "plume --resolution 256 --seed 7"},
    {"smoke_sphere.vdb", "smoke-sphere --resolution 96 --seed 7"},
};

std::vector<std::string> shippedScenes() {
    std::vector<std::string> names;
    for (const auto& e :
         fs::directory_iterator(fs::path(mirage::test::sourceDir()) / "assets" / "scenes"))
        if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

class GalleryNoise : public ::testing::TestWithParam<std::string> {};

TEST_P(GalleryNoise, StatedPresetWithinRelMse1e2OfFourTimesTheSamples) {
    const std::string name = GetParam(), file = name + ".toml";
    const std::string text = slurp(mirage::test::shippedScene(file));
    const std::string dir = mirage::test::tempDir();
    std::string scene, log;
    const std::regex cache(R"(file = "([a-z_0-9]+\.vdb)\")");
    if (text.find("shared/data") != std::string::npos) {
        if (mirage::test::sharedData().empty())
            GTEST_SKIP() << name << " reads ../shared/data, which is absent";
        scene = mirage::test::shippedScene(file);  // in place: its path to the data is relative
    } else if (!std::regex_search(text, cache)) {
        // In place: the meshes, IES profiles and shaders it reads are beside it in assets/.
        scene = mirage::test::shippedScene(file);
    } else {
        scene = mirage::test::shippedSceneCopy(dir, file);
        for (std::sregex_iterator m(text.begin(), text.end(), cache), end; m != end; ++m) {
            const std::string vdb = (*m)[1];
            ASSERT_TRUE(kCaches.count(vdb)) << name << " reads " << vdb << ": add its make-asset";
            if (fs::exists(dir + "/" + vdb)) continue;
            const std::string kind = kCaches.at(vdb);
            const std::string asset = kind.substr(0, kind.find(' '));
            const std::string args = kind.size() > asset.size() ? kind.substr(asset.size()) : "";
            ASSERT_EQ(mirage::test::runMirage(
                          "make-asset " + asset + " -o '" + dir + "/" + vdb + "'" + args, &log),
                      0)
                << log;
        }
    }
    // A quarter of the stated resolution, at least 16 pixels a side.
    std::smatch r;
    ASSERT_TRUE(std::regex_search(text, r, std::regex(R"(resolution = \[ *(\d+) *, *(\d+) *\])")));
    const int w = std::max(16, (std::stoi(r[1]) + 3) / 4),
              h = std::max(16, (std::stoi(r[2]) + 3) / 4);
    const std::string res = std::to_string(w) + "x" + std::to_string(h);
    const std::string reference = dir + "/final.exr";
    // Its preview in the temporary folder too, not at the scene's [output] preview.
    ASSERT_EQ(mirage::test::runMirage("render '" + scene + "' --quality final --seed 1001 " +
                                          "--resolution " + res + " --threads 2 -q -o '" +
                                          reference + "' --preview '" + dir + "/final.png'",
                                      &log),
              0)
        << log;
    ASSERT_EQ(mirage::test::runMirage("tradeoff '" + scene + "' --reference '" + reference +
                                          "' --vary film.seed=1 --resolution " + res +
                                          " --threads 2 -q -o '" + dir + "/noise_'",
                                      &log),
              0)
        << log;
    // setting,seconds,rmse,relmse,mean_bias,film.seed
    std::istringstream csv(slurp(dir + "/noise_tradeoff.csv"));
    std::string header, row;
    std::getline(csv, header);
    std::getline(csv, row);
    std::vector<std::string> cells;
    std::stringstream cs(row);
    for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
    ASSERT_GE(cells.size(), 5u) << row;
    const double seconds = std::atof(cells[1].c_str()), relMse = std::atof(cells[3].c_str());
    std::printf("%-22s %s  preset render %.1f s  relMSE %.4f against 4x the samples\n",
                name.c_str(), res.c_str(), seconds, relMse);
    EXPECT_LE(relMse, 1e-2) << name << ": visible noise at its stated preset";
}

INSTANTIATE_TEST_SUITE_P(Shipped, GalleryNoise, ::testing::ValuesIn(shippedScenes()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
