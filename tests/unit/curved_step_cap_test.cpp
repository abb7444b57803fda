// The hard cap on ODE steps per curved path (CurvedPathSettings::maxSteps, the scene's [refraction]
// max_steps) is reported, never silent (docs/curved-light.md, "The step cap"): a photon flight or a
// camera ray stopped by it goes on straight and is counted in the capped paths of the photon pass,
// of the render summary and of the EXR metadata; the image stays finite.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "film/image_io.h"
#include "geometry/geometry_scene.h"
#include "light/light.h"
#include "photon/photon_pass.h"
#include "test_support.h"

namespace mirage {
namespace {

TEST(CurvedStepCap, PhotonPassCountsFlightsStoppedByTheStepCap) {
    // A spot light 1 m above a ground aims horizontally in n = 1 − 0.05·y: the beam lands
    // ~6.3 m away, 63 chords of 0.1 m; three steps stop every flight first.
    GeometryScene geo;
    // Black: each photon stores once, where it lands.
    const int m = geo.addMaterial(Material::diffuse("ground", Spectrum(0.f)));
    geo.addQuad(Vec3(-100, 0, 100), Vec3(200, 0, 0), Vec3(0, 0, -200), m);
    geo.commit();
    auto spot = makeSpotLight(Vec3(0, 1, 0), Vec3(1, 0, 0), 1.f, 0.05f, 0.1f, Spectrum(1.f));
    const LinearIndexField field(1.0, -0.05);
    PhotonPassSettings ps;
    ps.photons = 500;
    ps.seed = 7;
    ps.progress = Progress::Mode::Quiet;
    ps.storeFirstInteraction = true;
    ps.field = std::make_shared<const LinearIndexField>(field);
    ps.curvedPath.maxStep = 0.1;
    PhotonPassStats uncapped;
    const PhotonMapLists landed = tracePhotonMaps({spot.get()}, {}, &geo, ps, &uncapped);
    EXPECT_EQ(uncapped.cappedPaths, 0u);
    EXPECT_GT(landed.surfaceGlobal.size(), 400u);

    ps.curvedPath.maxSteps = 3;
    PhotonPassStats capped;
    const PhotonMapLists maps = tracePhotonMaps({spot.get()}, {}, &geo, ps, &capped);
    // Every photon that left the spot with power was stopped (the rim of the cone has none).
    EXPECT_GE(capped.cappedPaths, uint64_t(0.95 * double(ps.photons)));
    EXPECT_LE(capped.cappedPaths, ps.photons);
    EXPECT_EQ(capped.nonFinite, 0u);
    // Straight on from 0.3 m of path, turned down by only ~0.015 rad: the photons land ~66 m
    // away instead of ~6.3 m (the bias that the count reports).
    auto meanX = [](const PhotonList& list) {
        double sum = 0;
        for (const Photon& p : list) sum += p.p.x;
        return list.empty() ? 0.0 : sum / double(list.size());
    };
    EXPECT_LT(meanX(landed.surfaceGlobal), 7.0);
    EXPECT_GT(meanX(maps.surfaceGlobal), 30.0);
}

// A floor under a point light, seen from 4 m; `refraction` is the [refraction] table.
std::string floorScene(const std::string& dir, const std::string& name,
                       const std::string& integrator, const std::string& refraction) {
    const std::string path = dir + "/" + name + ".toml";
    std::ofstream f(path);
    f << "[film]\nresolution = [8, 8]\nspp = 1\nseed = 2\n"
         "[render]\nintegrator = \"" << integrator << "\"\nphotons = 2000\n"
         "[camera]\nposition = [0, 1.5, 4]\nlook_at = [0, 0, 0]\nfov = 40\n"
         "[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\npower = 100\n"
         "[[material]]\nname = \"floor\"\ntype = \"diffuse\"\nreflectance = 0.5\n"
         "[[shape]]\ntype = \"quad\"\ncorner = [-3, 0, 3]\nedge_u = [6, 0, 0]\n"
         "edge_v = [0, 0, -6]\nmaterial = \"floor\"\n"
      << refraction;
    return path;
}

struct CapRender {
    uint64_t capped = 0;
    std::map<std::string, std::string> meta;
    std::string log;
};

CapRender renderCapped(const std::string& dir, const std::string& name,
                       const std::string& integrator, int maxSteps) {
    std::string refraction = "[refraction]\nprofile = \"linear\"\nk = -0.05\nmax_step = 0.1\n";
    if (maxSteps > 0) refraction += "max_steps = " + std::to_string(maxSteps) + "\n";
    const std::string exr = dir + "/" + name + ".exr";
    CapRender r;
    EXPECT_EQ(test::runMirage("render '" + floorScene(dir, name, integrator, refraction) +
                                  "' -o '" + exr + "' --threads 2",
                              &r.log),
              0)
        << r.log;
    const Image image = readExr(exr, &r.meta);
    int bad = 0;
    for (float v : image.rgba) bad += !std::isfinite(v);
    EXPECT_EQ(bad, 0) << name;
    EXPECT_TRUE(r.meta.count("mirage:capped_paths")) << name;
    r.capped = std::stoull(r.meta["mirage:capped_paths"]);
    return r;
}

TEST(CurvedStepCap, RenderReportsCameraRaysAndPhotonsStoppedByTheStepCap) {
    const std::string dir = test::tempDir();
    // Camera rays: 4 m to the floor in 0.1 m chords is 40 steps; 2 stop each of the 64.
    EXPECT_EQ(renderCapped(dir, "single_free", "single", 0).capped, 0u);
    const CapRender single = renderCapped(dir, "single_capped", "single", 2);
    EXPECT_GE(single.capped, 64u);
    EXPECT_NE(single.log.find("capped paths " + std::to_string(single.capped)),
              std::string::npos)
        << single.log;
    // Photons too (the photon integrator bends them in a field that curves in the scene): the
    // pass's figures come through the curved-camera wrapper to the EXR and the summary.
    const CapRender photon = renderCapped(dir, "photon_capped", "photon", 2);
    EXPECT_GE(photon.capped, 64u + 1000u);
    ASSERT_TRUE(photon.meta.count("mirage:photons_traced"));
    EXPECT_EQ(photon.meta.at("mirage:photons_traced"), "2000");
    EXPECT_NE(photon.log.find("photons: 2000 traced"), std::string::npos) << photon.log;
}

TEST(CurvedStepCap, MaxStepsKeyIsRangeChecked) {
    const std::string dir = test::tempDir();
    std::string log;
    EXPECT_NE(test::runMirage("info '" +
                                  floorScene(dir, "bad", "single",
                                             "[refraction]\nprofile = \"linear\"\nk = 0.1\n"
                                             "max_steps = 0\n") +
                                  "'",
                              &log),
              0);
    EXPECT_NE(log.find("max_steps"), std::string::npos) << log;
}

}  // namespace
}  // namespace mirage
