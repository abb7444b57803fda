// Photons on curved paths (docs/curved-light.md): with a [refraction] field the photon pass follows
// Fermat paths chord by chord (PhotonWalk::flyCurved), and the render pass takes direct light from
// the photon maps. A collimated beam bent by n = n0 + k·y lands where the exact catenary
// (linear_profile_path.h) meets the ground; a flat field leaves the render's bits alone (the
// weak-field comparisons with straight light are in tests/physics/weak_field_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "film/image_io.h"
#include "geometry/geometry_scene.h"
#include "light/light.h"
#include "medium/linear_profile_path.h"
#include "photon/photon_pass.h"
#include "test_support.h"

namespace mirage {
namespace {

// Arc length at which the exact path in n = n0 + k·y from o along d reaches y = 0.
double exactArcToGround(double n0, double k, const Vec3d& o, const Vec3d& d) {
    double lo = 0, hi = 200;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        const LinearProfilePath p = exactLinearProfilePath(n0, k, Vec3d(0, 1, 0), o, d, mid);
        (p.endPoint.y > 0 ? lo : hi) = mid;
    }
    return lo;
}

TEST(CurvedPhotons, CollimatedBeamLandsOnTheCatenarysSpot) {
    // A spot light 1 m above a black ground aims horizontally (cone 0.05°–0.1°: a float
    // cosine resolves no narrower): straight,
    // no photon would reach the ground; in n = 1 − 0.05·y the beam bends down and lands
    // ~6.3 m away. Photons arriving straight from the light are stored where paths curve.
    GeometryScene geo;
    const int m = geo.addMaterial(Material::diffuse("ground", Spectrum(0.f)));
    geo.addQuad(Vec3(-100, 0, 100), Vec3(200, 0, 0), Vec3(0, 0, -200), m);  // y = 0
    geo.commit();
    const Vec3 o(0, 1, 0), d(1, 0, 0);
    auto spot = makeSpotLight(o, d, 1.f, 0.05f, 0.1f, Spectrum(1.f));
    const double n0 = 1.0, k = -0.05;
    const LinearIndexField field(n0, k);
    PhotonPassSettings ps;
    ps.photons = 2000;
    ps.seed = 3;
    ps.progress = Progress::Mode::Quiet;
    ps.storeFirstInteraction = true;
    ps.field = std::make_shared<const LinearIndexField>(field);
    ps.curvedPath.tolerance = 1e-9;
    ps.curvedPath.maxStep = 0.1;
    PhotonPassStats stats;
    const PhotonMapLists maps = tracePhotonMaps({spot.get()}, {}, &geo, ps, &stats);
    // Every photon lands, directly (but the few the spot's falloff gives no power at its rim).
    ASSERT_GT(maps.surfaceGlobal.size(), size_t(0.95 * double(ps.photons)));
    EXPECT_TRUE(maps.surfaceCaustic.empty());
    const double l = exactArcToGround(n0, k, Vec3d(o), Vec3d(d));
    const LinearProfilePath exact =
        exactLinearProfilePath(n0, k, Vec3d(0, 1, 0), Vec3d(o), Vec3d(d), l);
    double meanX = 0, meanZ = 0, worst = 0, worstAngle = 0;
    for (const Photon& p : maps.surfaceGlobal) {
        meanX += p.p.x;
        meanZ += p.p.z;
        worst = std::max(worst, length(Vec3d(p.p) - exact.endPoint));
        worstAngle =
            std::max(worstAngle, std::acos(std::min(1.0, dot(Vec3d(p.wi), exact.endDirection))));
    }
    meanX /= double(maps.surfaceGlobal.size());
    meanZ /= double(maps.surfaceGlobal.size());
    // The cone (≤ 0.1° = 1.7e−3 rad) spreads the spot by centimetres; its mean lies on the
    // central path (to second order in the cone's angle).
    std::printf("spot: mean x %.5f m, exact %.5f m, mean z %.5f m, worst %.4f m, angle %.2e\n",
                meanX, exact.endPoint.x, meanZ, worst, worstAngle);
    EXPECT_NEAR(meanX, exact.endPoint.x, 5e-3);
    EXPECT_NEAR(meanZ, 0.0, 2e-3);
    EXPECT_LT(worst, 0.1);
    // The stored direction is the last chord's: within half a 0.1 m chord's turn (h/2R) of the
    // tangent, R = n/|∇n| ≈ 19 m.
    EXPECT_LT(worstAngle, 0.005);
    // The straight flight: without the field nothing reaches the ground.
    ps.field = nullptr;
    const PhotonMapLists straight = tracePhotonMaps({spot.get()}, {}, &geo, ps, nullptr);
    EXPECT_TRUE(straight.surfaceGlobal.empty());
}

TEST(CurvedPhotons, FlatFieldLeavesThePhotonRenderBitIdentical) {
    // No index gradient anywhere: the straight photon pass, shadow rays and all, bit for bit.
    const std::string dir = test::tempDir();
    auto scene = [&](const std::string& name, const std::string& extra) {
        return test::writeFile(
            dir, name,
            std::string("[film]\nresolution = [12, 12]\nspp = 2\nseed = 8\n"
                        "[render]\nintegrator = \"photon\"\nphotons = 20000\n"
                        "[camera]\nposition = [0, 1.5, 4]\nlook_at = [0, 0, 0]\nfov = 40\n"
                        "[[light]]\ntype = \"point\"\nposition = [0, 2, 0]\npower = 100\n"
                        "[[material]]\nname = \"floor\"\ntype = \"diffuse\"\nreflectance = 0.5\n"
                        "[[shape]]\ntype = \"quad\"\ncorner = [-3, 0, 3]\nedge_u = [6, 0, 0]\n"
                        "edge_v = [0, 0, -6]\nmaterial = \"floor\"\n") +
                extra);
    };
    const Image plain = test::renderToExr(scene("plain.toml", ""), dir + "/plain.exr", "");
    const Image flat = test::renderToExr(
        scene("flat.toml", "[refraction]\nprofile = \"linear\"\nn0 = 1.0003\nk = 0\n"),
        dir + "/flat.exr", "");
    ASSERT_EQ(plain.rgba.size(), flat.rgba.size());
    EXPECT_TRUE(plain.rgba == flat.rgba);
    EXPECT_GT(test::channelMean(plain, 0), 0.0);
}

}  // namespace
}  // namespace mirage
