// assets/scenes/smoke1_sun.toml reads the real cache from ../shared/data by a path relative to
// the scene file. With the data it loads (photon integrator, the sun, colour filmed per light
// colour: render/achromatic_film.h); copied where that path leads nowhere, it stops with one
// message naming the missing file and exit code 1.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "test_support.h"

namespace mirage {
namespace {

namespace fs = std::filesystem;

std::string shippedScene() { return test::shippedScene("smoke1_sun.toml"); }

TEST(Smoke1SunScene, LoadsTheSharedCacheWithThePhotonIntegrator) {
    MIRAGE_REQUIRE_SHARED(smoke, "vdb/smoke1.vdb");
    ASSERT_TRUE(fs::exists(shippedScene())) << shippedScene();
    std::string out;
    ASSERT_EQ(test::runMirage("info '" + shippedScene() + "'", &out), 0) << out;
    EXPECT_NE(out.find("smoke1.vdb"), std::string::npos) << out;
    EXPECT_NE(out.find("integrator 'photon'"), std::string::npos) << out;
    EXPECT_NE(out.find("distant light"), std::string::npos) << out;
    // Grey smoke under a warm sun and a blue fill: filmed per light colour, no colour noise.
    EXPECT_NE(out.find("grey media, 2 light colours"), std::string::npos) << out;
}

TEST(Smoke1SunScene, WithoutTheSharedDataOneMessageNamesTheFile) {
    ASSERT_TRUE(fs::exists(shippedScene())) << shippedScene();
    const std::string dir = test::tempDir() + "/a/b/c";
    fs::create_directories(dir);
    fs::copy_file(shippedScene(), dir + "/smoke1_sun.toml");
    std::string out;
    EXPECT_EQ(test::runMirage("render '" + dir + "/smoke1_sun.toml' -o '" + dir + "/x.exr'", &out),
              1);
    EXPECT_NE(out.find("smoke1.vdb"), std::string::npos) << out;
    EXPECT_NE(out.find("not found"), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir + "/x.exr"));
}

}  // namespace
}  // namespace mirage
