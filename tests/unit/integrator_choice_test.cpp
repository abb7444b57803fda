// The default integrator (`[render] integrator = "auto"`, scene/integrator_choice.cpp): per
// scene, the method that renders all the light, with its reason; a named integrator stays; the
// reason reaches `mirage info`.
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "film/color.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace mirage;

namespace {

// A homogeneous box of one grey component (σa, σs in 1/m) under a sun, plus `extra` TOML. Its
// side is 2 m, so its typical optical depth (integrator_choice.cpp) is 2 (σa + σs).
std::string boxScene(const std::string& dir, const std::string& name, float sigmaA, float sigmaS,
                     const std::string& extra = "", int spp = 1) {
    const std::string shader = dir + "/" + name + "_shader.toml";
    std::ofstream(shader) << "[[component]]\nname = \"fog\"\ngrid = \"\"\nsigma_a = " << sigmaA
                          << "\nsigma_s = " << sigmaS << "\n";
    const std::string path = dir + "/" + name + ".toml";
    std::ofstream(path) << "[film]\nresolution = [8, 8]\nspp = " << spp << "\n"
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

// Rule 4: dense (optical depth ≥ 10), bright (albedo ≥ 0.9), grey smoke renders with progressive
// photon passes, film.spp of them as passes of one sample (or the stated pass_spp) with k = 32
// (or the stated k); just below either threshold, or with a surface in the scene, it stays with
// the path tracer.
TEST(IntegratorChoice, DenseBrightSmokeGetsProgressivePhotonPasses) {
    const std::string dir = test::tempDir();
    Scene dense = load(boxScene(dir, "dense", 0.25f, 9.75f, "", 10));  // depth 20, albedo 0.975
    EXPECT_EQ(dense.integrator, "photon");
    EXPECT_NE(dense.integratorWhy.find("dense, bright, grey smoke (albedo 0.98"), std::string::npos)
        << dense.integratorWhy;
    EXPECT_NE(dense.integratorWhy.find("optical depth 20)"), std::string::npos)
        << dense.integratorWhy;
    EXPECT_EQ(dense.passes.maxPasses, 10);  // 10 samples in passes of 1
    EXPECT_EQ(dense.statedPasses, 10);
    EXPECT_EQ(dense.passes.sppPerPass, 1);
    EXPECT_EQ(dense.photon.k, 32);
    EXPECT_EQ(dense.photon.firstPassPhotons, 20000u);  // a fifth of the default 10⁵
    Scene own = load(boxScene(dir, "own", 0.25f, 9.75f,
                              "[render]\npass_spp = 4\nk = 8\nfirst_pass_photons = 0\n", 10));
    EXPECT_EQ(own.passes.maxPasses, 3);  // 10 samples in passes of 4
    EXPECT_EQ(own.passes.sppPerPass, 4);
    EXPECT_EQ(own.photon.k, 8);
    EXPECT_EQ(own.photon.firstPassPhotons, 0u);
    EXPECT_EQ(load(boxScene(dir, "thinner", 0.24f, 4.5f)).integrator, "volpath");  // depth 9.5
    EXPECT_EQ(load(boxScene(dir, "darker", 2.f, 16.f)).integrator, "volpath");     // albedo 0.89
    Scene floor = load(boxScene(dir, "floor", 0.25f, 9.75f,
                                "[[shape]]\ntype = \"quad\"\ncorner = [-2, -1, 2]\n"
                                "edge_u = [4, 0, 0]\nedge_v = [0, 0, -4]\nmaterial = \"white\"\n"
                                "[[material]]\nname = \"white\"\ntype = \"diffuse\"\n"));
    EXPECT_EQ(floor.integrator, "volpath");
    // A scene that states its passes keeps them; a named integrator takes film.spp again.
    Scene stated = load(boxScene(dir, "stated", 0.25f, 9.75f, "[render]\npasses = 7\n"));
    EXPECT_EQ(stated.integrator, "photon");
    EXPECT_EQ(stated.passes.maxPasses, 7);
    Scene named =
        load(boxScene(dir, "named_dense", 0.25f, 9.75f, "", 10), {"render.integrator=volpath"});
    EXPECT_EQ(named.passes.maxPasses, 0);
    EXPECT_EQ(named.passes.sppPerPass, 4);
    EXPECT_EQ(named.photon.k, 0);
    EXPECT_EQ(named.photon.firstPassPhotons, 0u);
    Scene chosen = load(boxScene(dir, "rechosen", 0.25f, 9.75f, "", 10));
    chosen.integrator = "volpath";  // what --integrator does after loading
    resolveAutoIntegrator(&chosen);
    EXPECT_EQ(chosen.passes.maxPasses, 0);
    EXPECT_EQ(chosen.statedPasses, 0);
    EXPECT_EQ(chosen.passes.sppPerPass, 4);
    EXPECT_EQ(chosen.photon.k, 0);
    EXPECT_EQ(chosen.photon.firstPassPhotons, 0u);
}

// What a user sees: `mirage render` of the dense box renders film.spp as passes (EXR metadata),
// --spp sets their number, --integrator volpath renders film.spp without passes, and `mirage
// info` says all of it.
TEST(IntegratorChoice, DenseSmokeRendersItsSamplesAsPhotonPasses) {
    const std::string dir = test::tempDir();
    const std::string path =
        boxScene(dir, "dense_cli", 0.25f, 9.75f, "[render]\nphotons = 4000\n", 8);
    std::string out;
    auto render = [&](const std::string& args, const std::string& exr) {
        return test::renderMetadata(path, args, dir + "/" + exr);
    };
    std::map<std::string, std::string> plain = render("", "auto.exr");
    EXPECT_EQ(plain["mirage:passes"], "8");
    EXPECT_EQ(plain["mirage:samples"], std::to_string(8 * 8 * 8));
    EXPECT_EQ(render("--spp 16", "more.exr")["mirage:passes"], "16");
    // --quality scales the passes (draft 1/16, final 4) and keeps each map's photons (4000
    // stated here, 10⁵ unstated): the preset's 10⁶ or 4·10⁶ photons are a one-map render's.
    // The first pass traces a fifth of them.
    std::map<std::string, std::string> draft = render("--quality draft", "draft.exr");
    EXPECT_EQ(draft["mirage:passes"], "1");
    EXPECT_EQ(draft["mirage:photons_traced"], "800");
    std::map<std::string, std::string> final = render("--quality final", "final.exr");
    EXPECT_EQ(final["mirage:passes"], "32");
    EXPECT_EQ(final["mirage:photons_traced"], std::to_string(800 + 31 * 4000));
    std::map<std::string, std::string> path_traced = render("--integrator volpath", "vp.exr");
    EXPECT_EQ(path_traced.count("mirage:passes"), 0u);
    ASSERT_EQ(0, test::runMirage("info '" + path + "'", &out)) << out;
    EXPECT_NE(out.find("8 passes of 1 spp (a photon map each)"), std::string::npos) << out;
    EXPECT_NE(out.find("passes of 1 spp, a photon map of 4000 photons each (the first 800), k 32"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("integrator: auto: dense, bright, grey smoke"), std::string::npos) << out;
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
    EXPECT_NE(s.integratorWhy.find("those to lamps stay straight"), std::string::npos)
        << s.integratorWhy;
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
