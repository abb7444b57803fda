// The default integrator (`[render] integrator = "auto"`, scene/integrator_choice.cpp): per
// scene, the method that renders all the light, with its reason; a named integrator stays; the
// reason reaches `mirage info`.
#include <gtest/gtest.h>

#include <fstream>

#include "film/color.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace mirage;

namespace {

// A homogeneous box of one grey component (σa, σs in 1/m) under a sun, plus `extra` TOML.
std::string boxScene(const std::string& dir, const std::string& name, float sigmaA, float sigmaS,
                     const std::string& extra = "") {
    const std::string shader = dir + "/" + name + "_shader.toml";
    std::ofstream(shader) << "[[component]]\nname = \"fog\"\ngrid = \"\"\nsigma_a = " << sigmaA
                          << "\nsigma_s = " << sigmaS << "\n";
    const std::string path = dir + "/" + name + ".toml";
    std::ofstream(path) << "[film]\nresolution = [8, 8]\nspp = 1\n"
                        << "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n"
                        << "[[volume]]\nbox = { min = [-1, -1, -1], max = [1, 1, 1] }\nshader = \""
                        << shader << "\"\n"
                        << "[[light]]\ntype = \"sun\"\ndirection = [0, -1, 0]\n"
                        << extra;
    return path;
}

Scene load(const std::string& path, const std::vector<std::string>& sets = {}) {
    ColorPipeline color;
    return loadScene(path, LoadOptions{1, sets}, color);
}

}  // namespace

TEST(IntegratorChoice, ScatteringMediaGetThePathTracer) {
    const std::string dir = test::tempDir();
    Scene s = load(boxScene(dir, "fog", 0.1f, 2.f));
    EXPECT_EQ(s.integrator, "volpath");
    EXPECT_NE(s.integratorWhy.find("auto: media scatter"), std::string::npos) << s.integratorWhy;
    // Multiple scattering is on, as `mirage info` reports it.
    for (const PhysicsTerm& t : s.physics()) {
        if (t.name == "multiple scattering") {
            EXPECT_TRUE(t.active) << t.why;
        }
    }
}

TEST(IntegratorChoice, PurelyAbsorbingMediaGetSingleWhichIsExactThere) {
    const std::string dir = test::tempDir();
    Scene s = load(boxScene(dir, "ink", 2.f, 0.f));
    EXPECT_EQ(s.integrator, "single");
    EXPECT_NE(s.integratorWhy.find("nothing scatters"), std::string::npos) << s.integratorWhy;
}

TEST(IntegratorChoice, GlassAndALightGetThePhotonMapperForCaustics) {
    const std::string dir = test::tempDir();
    Scene s = load(boxScene(dir, "caustic", 0.1f, 2.f,
                            "[[material]]\nname = \"glass\"\ntype = \"dielectric\"\n"
                            "[[shape]]\ntype = \"sphere\"\ncenter = [0, 2, 0]\nradius = 0.5\n"
                            "material = \"glass\"\n"));
    EXPECT_EQ(s.integrator, "photon");
    EXPECT_NE(s.integratorWhy.find("caustics"), std::string::npos) << s.integratorWhy;
}

TEST(IntegratorChoice, CurvedLightGetsThePhotonMapper) {
    const std::string dir = test::tempDir();
    Scene s = load(boxScene(dir, "bent", 0.1f, 2.f,
                            "[refraction]\nprofile = \"linear\"\nn0 = 1.0\nk = 0.01\n"));
    EXPECT_EQ(s.integrator, "photon");
    EXPECT_NE(s.integratorWhy.find("bends"), std::string::npos) << s.integratorWhy;
}

TEST(IntegratorChoice, ANamedIntegratorStaysAndAutoCanBeAskedFor) {
    const std::string dir = test::tempDir();
    const std::string path = boxScene(dir, "named", 0.1f, 2.f);
    Scene single = load(path, {"render.integrator=single"});
    EXPECT_EQ(single.integrator, "single");
    EXPECT_TRUE(single.integratorWhy.empty());
    Scene chosen = load(path, {"render.integrator=auto"});
    EXPECT_EQ(chosen.integrator, "volpath");
    std::string out;
    ASSERT_EQ(0, test::runMirage("info '" + path + "'", &out)) << out;
    EXPECT_NE(out.find("integrator 'volpath'"), std::string::npos) << out;
    EXPECT_NE(out.find("integrator: auto: media scatter"), std::string::npos) << out;
}
