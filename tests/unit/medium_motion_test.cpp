// MediumMotion (medium/medium_motion.h) alone: the blur radius a velocity grid gives, a path's
// advected lookup point at its time (and the exact point, with no velocity lookup, for a still
// path or a still medium), and a keyed transform placing the path's volume where the keys say.
// The medium it moves is tested in motion_blur_test.cpp and keyed_motion_test.cpp.
#include "medium/medium_motion.h"

#include <gtest/gtest.h>

#include "test_grids.h"
#include "test_support.h"
#include "volume/vdb_file.h"

using namespace mirage;

namespace {

// A uniform wind of (2, 0, −1) m/s over a 9³ box of voxels.
VectorGrid uniformWind() {
    TestGridSpec vel;
    vel.name = "vel";
    vel.valueType = "vec3s";
    vel.gridClass = "unknown";
    vel.voxelSize = 0.1;
    for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j)
            for (int k = -4; k <= 4; ++k) vel.voxels.push_back({i, j, k, 0.0, Vec3d(2, 0, -1)});
    const std::string path = test::tempDir() + "/wind.vdb";
    writeTestGrids(path, {vel});
    return loadVectorGrid(path, "vel");
}

}  // namespace

TEST(MediumMotion, StillByDefault) {
    const MediumMotion still;
    EXPECT_FALSE(still.moving());
    EXPECT_FALSE(still.transformMoves());
    EXPECT_EQ(still.blurRadius(), 0.f);
    const Transform xf = Transform::translate(Vec3d(1, 2, 3));
    MediumMotion::Path path(still, xf, xf.inverse());
    path.setTimeOffset(0.01f);
    EXPECT_EQ(path.timeOffset(), 0.01f);  // the path's time is kept...
    const Vec3 p(0.1f, -0.2f, 0.3f);
    EXPECT_EQ(path.lookupPoint(p), p);  // ...but a still medium is read where it is
    EXPECT_EQ(path.objectToWorld().point(p), xf.point(p));
}

TEST(MediumMotion, VelocityAdvectsLookupsBackAlongTheFlow) {
    MediumMotion motion;
    motion.setVelocity(uniformWind(), 0.5f, 0.04f);
    ASSERT_TRUE(motion.moving());
    // R = max|v| · |scale| · maxTimeOffset = √5 · 0.5 · 0.04.
    EXPECT_NEAR(motion.blurRadius(), std::sqrt(5.f) * 0.02f, 1e-6f);
    EXPECT_FLOAT_EQ(motion.reachPerVelocity(), 0.02f);
    MediumMotion::Path path(motion, Transform(), Transform());
    const Vec3 p(0.05f, 0.1f, -0.15f);
    EXPECT_EQ(path.lookupPoint(p), p);  // at the frame's time
    EXPECT_EQ(path.displacement(p), Vec3(0.f));
    path.setTimeOffset(-0.04f);
    const Vec3 d = path.displacement(p);  // v · scale · Δt = (−0.04, 0, 0.02)
    EXPECT_NEAR(d.x, -0.04f, 1e-6f);
    EXPECT_NEAR(d.y, 0.f, 1e-6f);
    EXPECT_NEAR(d.z, 0.02f, 1e-6f);
    EXPECT_EQ(path.lookupPoint(p), p - d);
    // A zero scale, or no shutter, moves nothing.
    MediumMotion none;
    none.setVelocity(uniformWind(), 0.f, 0.04f);
    EXPECT_FALSE(none.moving());
}

TEST(MediumMotion, KeysPlaceThePathsVolumeAtItsTime) {
    TransformParts a, b;
    b.translate = Vec3d(2, 0, 0);
    MediumMotion motion;
    motion.setTransformKeys(KeyedTransform({TransformKey{-0.5, a}, TransformKey{0.5, b}}), -0.5f,
                            0.5f);
    ASSERT_TRUE(motion.transformMoves());
    EXPECT_FALSE(motion.moving());
    const Transform still = motion.transformKeys().at(0.0);
    MediumMotion::Path path(motion, still, still.inverse());
    path.setTimeOffset(0.25f);
    const Vec3 o = path.objectToWorld().point(Vec3(0.f));
    EXPECT_FLOAT_EQ(o.x, 1.5f);
    EXPECT_EQ(path.worldToObject().point(o), Vec3(0.f));
    // The world bounds cover the box at every time of the shutter.
    Bounds3 unit;
    unit.expand(Vec3(0.f));
    unit.expand(Vec3(1.f));
    const Bounds3 swept = motion.sweep(unit, still);
    EXPECT_LE(swept.lo.x, 0.f);
    EXPECT_GE(swept.hi.x, 3.f);
}
