// Velocity motion blur (Medium::setMotion, [camera] shutter, [output] fps): the photon pass's
// times, bit-identity where nothing moves, determinism, the dilated majorant and the velocity
// grids' rules. The blurred render against the mean of translated stills is in
// tests/physics/motion_blur_stills_test.cpp.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

#include "film/color.h"
#include "photon/photon_pass.h"
#include "puff_scene.h"
#include "render/integrator.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "test_grids.h"
#include "test_support.h"
#include "tools/asset_writer.h"
#include "volume/grid_lookup.h"
#include "volume/vdb_file.h"

namespace mirage {
namespace {

using namespace puff;

// The photon pass samples times too: each photon meets the puff where it is at its own time,
// so the stored photons of a puff translated uniformly over a length L spread like the still
// pass's convolved with that box: var_x grows by L²/12 (the sun is directional, so the
// photons' distribution moves with the puff), and their mean stays put.
TEST(MotionBlur, PhotonPassSamplesTimesInTheShutter) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    ColorPipeline color;
    auto moments = [&](const std::string& scenePath, float* lo, float* hi) {
        Scene scene = loadScene(scenePath, LoadOptions{}, color);
        PhotonPassSettings pass;
        pass.photons = 400000;
        pass.seed = 4;
        pass.storeFirstInteraction = true;  // every scattering, for enough of them
        pass.progress = Progress::Mode::Quiet;
        pass.shutterOpen = scene.render.camera.shutterOpen;
        pass.shutterClose = scene.render.camera.shutterClose;
        std::vector<const Light*> lights;
        for (const auto& l : scene.render.lights) lights.push_back(l.get());
        const PhotonList photons =
            tracePhotons(lights, scene.render.mediaPointers(), pass, nullptr);
        double n = 0, sx = 0, sxx = 0;
        *lo = kInfinity;
        *hi = -kInfinity;
        for (const Photon& p : photons) {
            n += 1;
            sx += p.p.x;
            sxx += double(p.p.x) * p.p.x;
            *lo = std::min(*lo, p.time);
            *hi = std::max(*hi, p.time);
        }
        EXPECT_GT(n, 5000);
        const double mean = sx / n;
        return std::make_pair(mean, sxx / n - mean * mean);
    };
    float lo, hi;
    const auto still = moments(writeScene(dir, "still", "", kStill), &lo, &hi);
    EXPECT_EQ(lo, 0.f);
    EXPECT_EQ(hi, 0.f);
    const auto blur = moments(writeScene(dir, "blur", kOpen, ""), &lo, &hi);
    const double halfShutter = 0.5 * kShutter / kFps;  // s
    EXPECT_GE(lo, -halfShutter);
    EXPECT_LE(hi, halfShutter);
    EXPECT_LT(lo, -0.9 * halfShutter);
    EXPECT_GT(hi, 0.9 * halfShutter);
    const double L = kSpeed * kShutter / kFps;
    EXPECT_NEAR(blur.first, still.first, 0.02);
    EXPECT_NEAR(blur.second, still.second + L * L / 12.0, 0.1 * L * L / 12.0);
}

TEST(MotionBlur, ZeroShutterIsBitIdenticalToNoBlur) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    // Velocity bound (by default) with the shutter [0, 0]; and blur switched off.
    const std::string zero = writeScene(dir, "zero", "[0, 0]", "");
    const std::string none = writeScene(dir, "none", "", kStill);
    for (const char* integrator : {"single", "volpath", "photon"}) {
        SCOPED_TRACE(integrator);
        Rendered a = renderScene(zero, 7, integrator), b = renderScene(none, 7, integrator);
        EXPECT_TRUE(sameFilm(a.film, b.film));
    }
}

TEST(MotionBlur, StillVelocityFieldBlursNothing) {
    // A zero velocity field with the shutter open: the time stream is separate from the path's,
    // so the render is the still one, bit for bit.
    const std::string dir = test::tempDir();
    writePuff(dir, Vec3d(0, 0, 0));
    Rendered blur = renderScene(writeScene(dir, "blur", kOpen, ""), 3, "single");
    Rendered still = renderScene(writeScene(dir, "still", "", kStill), 3, "single");
    EXPECT_TRUE(sameFilm(blur.film, still.film));
}

TEST(MotionBlur, SameSeedSameBitsForAnyThreadCount) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    const std::string scene = writeScene(dir, "blur", kOpen, "");
    std::vector<Film> films;
    for (int threads : {1, 2, 3}) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, size_t(threads));
        films.push_back(renderScene(scene, 11, "volpath").film);
    }
    EXPECT_TRUE(sameFilm(films[0], films[1]));
    EXPECT_TRUE(sameFilm(films[0], films[2]));
}

TEST(MotionBlur, DilatedMajorantBoundsEveryAdvectedLookup) {
    // A swirling, non-uniform field over a lumpy grid: σt at random points and times within the
    // shutter never exceeds the majorant cell the point lies in.
    const std::string dir = test::tempDir();
    TestGridSpec density, vel;
    density.voxelSize = vel.voxelSize = 0.1;
    vel.name = "vel";
    vel.valueType = "vec3s";
    vel.gridClass = "unknown";
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = -6; i <= 6; ++i)
        for (int j = -6; j <= 6; ++j)
            for (int k = -6; k <= 6; ++k) {
                if (u(rng) < 0.5) density.voxels.push_back({i, j, k, u(rng) * u(rng) * 4.0});
                vel.voxels.push_back(
                    {i, j, k, 0.0, Vec3d(-j * 0.8, i * 0.8, 3.0 * (u(rng) - 0.5))});
            }
    const std::string path = dir + "/lumpy.vdb";
    writeTestGrids(path, {density, vel});
    Medium m(test::greyShader(0.5f, 1.5f), {loadFloatGrid(path, "density")}, Transform(), 1.f);
    const float maxDt = 0.05f;
    MediumMotion motion;
    motion.setVelocity(loadVectorGrid(path, "vel"), 1.f, maxDt);
    m.setMotion(motion);
    ASSERT_TRUE(m.motion().moving());
    EXPECT_GT(m.motion().blurRadius(), 0.2f);
    const MajorantGrid& g = m.majorant();
    Medium::Context ctx(m);
    const Bounds3 b = g.bounds();
    int nonzero = 0;
    for (int n = 0; n < 200000; ++n) {
        const Vec3 p(float(b.lo.x + u(rng) * (b.hi.x - b.lo.x)),
                     float(b.lo.y + u(rng) * (b.hi.y - b.lo.y)),
                     float(b.lo.z + u(rng) * (b.hi.z - b.lo.z)));
        ctx.setTimeOffset(float((2.0 * u(rng) - 1.0) * maxDt));
        MediumPoint mp;
        m.eval(p, ctx, &mp);
        const float sigmaT = (mp.sigmaA + mp.sigmaS).maxValue();
        int c[3];
        for (int a = 0; a < 3; ++a)
            c[a] = std::min(g.res(a) - 1,
                            int((p[a] - b.lo[a]) / (b.hi[a] - b.lo[a]) * float(g.res(a))));
        ASSERT_LE(sigmaT, g.cell(c[0], c[1], c[2])) << "at " << p.x << ", " << p.y << ", " << p.z;
        nonzero += sigmaT > 0.f;
    }
    EXPECT_GT(nonzero, 1000);
}

TEST(MotionBlur, BadVelocityGridsGetTheRuleOrAClearError) {
    const std::string dir = test::tempDir();
    ColorPipeline color;
    writePuff(dir);
    // A scalar grid named as the velocity: refused, naming it.
    try {
        loadScene(writeScene(dir, "wrong", kOpen, "velocity = \"density\"\n"), LoadOptions{},
                  color);
        FAIL() << "expected an error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("'density'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("3-vector"), std::string::npos) << e.what();
    }
    // A grid the file lacks: refused, listing the file's grids.
    try {
        loadScene(writeScene(dir, "missing", kOpen, "velocity = \"wind\"\n"), LoadOptions{}, color);
        FAIL() << "expected an error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("'wind'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("'vel'"), std::string::npos) << e.what();
    }
    // Absurd magnitudes: a displacement thousands of times the puff's size is refused.
    writePuff(dir, Vec3d(1e7, 0, 0));
    try {
        loadScene(writeScene(dir, "absurd", kOpen, ""), LoadOptions{}, color);
        FAIL() << "expected an error";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("velocity grid 'vel'"), std::string::npos) << e.what();
    }
    // NaN and infinite vectors become 0 (the vector voxel rule): the render is finite.
    writePuff(dir, Vec3d(std::nan(""), 0, std::numeric_limits<double>::infinity()));
    Rendered r = renderScene(writeScene(dir, "nan", kOpen, ""), 1, "single");
    EXPECT_EQ(r.stats.nonFiniteSamples, 0u);
    EXPECT_EQ(r.stats.aboveMajorant, 0u);
}

TEST(MotionBlur, ThreeScalarGridsActAsOneVectorGrid) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    const std::string vec = dir + "/puff.vdb";
    // The same field as vel.x, vel.y, vel.z float grids (signed: −x here).
    TestGridSpec density;
    density.voxelSize = kVoxel;
    density.voxels = {{0, 0, 0, 1.0}, {1, 0, 0, 0.5}};
    std::vector<TestGridSpec> specs = {density};
    for (int a = 0; a < 3; ++a) {
        TestGridSpec c;
        c.name = std::string("vel.") + "xyz"[a];
        c.gridClass = "unknown";
        c.voxelSize = kVoxel;
        for (int i = -3; i <= 3; ++i)
            c.voxels.push_back({i, 0, 0, a == 0 ? -2.0 : a == 1 ? 0.5 : 0.0});
        specs.push_back(c);
    }
    const std::string path = dir + "/scalars.vdb";
    writeTestGrids(path, specs);
    VectorGrid v = loadVectorGridFromScalars(path, "vel");
    ASSERT_TRUE(v.valid());
    const Vec3 s = v.sample(v.accessor(), Vec3(0.f, 0.f, 0.f));
    EXPECT_FLOAT_EQ(s.x, -2.f);
    EXPECT_FLOAT_EQ(s.y, 0.5f);
    EXPECT_FLOAT_EQ(s.z, 0.f);
    EXPECT_EQ(v.name(), "vel");
}

TEST(MotionBlur, ProceduralPlumesCarryARisingSwirlingVelocity) {
    const std::string dir = test::tempDir();
    for (const char* kind : {"smoke", "fire"}) {
        SCOPED_TRACE(kind);
        const std::string path = dir + "/" + kind + ".vdb";
        writeProceduralAsset(kind, path, 32, 1);
        VectorGrid v = loadVectorGrid(path, "vel");
        EXPECT_FALSE(v.staggered());
        EXPECT_EQ(v.activeVoxels(), loadFloatGrid(path, "density").activeVoxels());
        EXPECT_GT(v.minMagnitude(), 0.1f);
        EXPECT_LT(v.maxMagnitude(), 4.f);
        // Rising on the axis; swirling counter-clockwise seen from above off it (+x → +z).
        const Vec3 axis = v.sample(v.accessor(), Vec3(0.f, 1.f, 0.f));
        EXPECT_GT(axis.y, 0.5f);
        const Vec3 side = v.sample(v.accessor(), Vec3(0.08f, 1.2f, 0.f));
        EXPECT_GT(side.z, 0.05f);
        EXPECT_GT(side.x, 0.f);  // spreading outwards as the plume widens
    }
}

TEST(MotionBlur, MantaflowSequenceRendersBlurred) {
    MIRAGE_REQUIRE_SHARED(frame8, "vdb/mantaflow_smoke.0008.vdb");
    const std::string pattern = frame8.substr(0, frame8.size() - 8) + "$F4.vdb";
    ColorPipeline color;
    for (int frame = 8; frame <= 10; ++frame) {
        SCOPED_TRACE(frame);
        LoadOptions blurred{frame, {"film.resolution=[48, 27]", "film.spp=4"}};
        blurred.shutter = ShutterFrames{-0.25, 0.25};
        Scene scene = loadScene(pattern, blurred, color);
        ASSERT_EQ(scene.volumes.size(), 1u);
        EXPECT_EQ(scene.volumes[0].velocity.grid, "velocity");
        EXPECT_TRUE(scene.volumes[0].velocity.velocity.staggered());
        EXPECT_TRUE(scene.render.media[0]->motion().moving());
        const RenderStats stats = renderStats(scene, "single");
        EXPECT_EQ(stats.aboveMajorant, 0u);
        EXPECT_EQ(stats.nonFiniteSamples, 0u);
        EXPECT_GT(stats.mediumLookups, 0u);
    }
}

}  // namespace
}  // namespace mirage
