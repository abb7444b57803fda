// Camera and volume motion within the shutter ([[camera.key]], turntables,
// [[volume.transform.key]]): a closed shutter renders the pose at the frame bit for bit, keys
// are checked, a keyed volume's world bounds hold it at every time, and the interpolation of
// keyed transforms. The blurred renders against the mean of stills are physics tests
// (tests/physics/keyed_motion_blur_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/keyed_transform.h"
#include "puff_scene.h"
#include "test_support.h"

namespace mirage {
namespace {

using namespace puff;

TEST(CameraMotion, ClosedShutterRendersTheKeyedPoseAtTheFrame) {
    // Keys halfway between at frame 1: the pose (0, 0, 4), bit for bit, and a turntable's
    // first frame is where the camera stands.
    const std::string dir = test::tempDir();
    writePuff(dir);
    PuffScene keyed = stillPuff();
    keyed.camera = "fov = 25\n";
    keyed.cameraKeys = kPanKeys;
    PuffScene turntable = stillPuff("[0, 0]");
    turntable.camera += "turntable = 16\n";
    const Rendered still = renderScene(writeScene(dir, "still", "", kStill), 5, "volpath");
    for (const std::string& shutter : {std::string(), std::string("[0, 0]")}) {
        keyed.shutter = shutter;
        EXPECT_TRUE(sameFilm(renderScene(writePuffScene(dir, "keyed", keyed), 5, "volpath").film,
                             still.film));
    }
    EXPECT_TRUE(
        sameFilm(renderScene(writePuffScene(dir, "tt", turntable), 5, "volpath").film, still.film));
}

TEST(CameraMotion, KeysAreCheckedWithTheirLine) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    ColorPipeline color;
    PuffScene p;
    p.camera = "fov = 25\n";
    p.cameraKeys = "[[camera.key]]\nframe = 0\nposition = [0, 0, 4]\nlook_at = [0, 0, 4]\n";
    EXPECT_THROW(loadScene(writePuffScene(dir, "self", p), LoadOptions{}, color), MirageError);
    p.cameraKeys = "[[camera.key]]\nposition = [0, 0, 4]\nlook_at = [0, 0, 0]\n";
    EXPECT_THROW(loadScene(writePuffScene(dir, "noframe", p), LoadOptions{}, color), MirageError);
    p.cameraKeys = kPanKeys + "[[camera.key]]\nframe = 2\nposition = [0, 0, 4]\n";
    try {
        loadScene(writePuffScene(dir, "twice", p), LoadOptions{}, color);
        ADD_FAILURE() << "two keys at one frame were accepted";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("same frame"), std::string::npos) << e.what();
        EXPECT_GT(e.location().line, 0);
    }
}

TEST(VolumeMotion, ClosedShutterRendersTheTransformAtTheFrame) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    PuffScene keyed = stillPuff("[0, 0]");
    keyed.transformKeys = kTranslateKeys;
    const Rendered still = renderScene(writeScene(dir, "still", "", kStill), 5, "photon");
    EXPECT_TRUE(
        sameFilm(renderScene(writePuffScene(dir, "keyed", keyed), 5, "photon").film, still.film));
}

TEST(VolumeMotion, WorldBoundsHoldTheVolumeAtEveryTime) {
    const std::string dir = test::tempDir();
    writePuff(dir);
    PuffScene p = stillPuff(kOpen);
    p.transformKeys =
        "[[volume.transform.key]]\nframe = 0\nrotate = [-90, 0, 0, 1]\ntranslate = [0, 1, 0]\n"
        "[[volume.transform.key]]\nframe = 2\nrotate = [90, 0, 0, 1]\ntranslate = [0, 1, 0]\n";
    ColorPipeline color;
    Scene scene = loadScene(writePuffScene(dir, "turning", p), LoadOptions{}, color);
    const Medium& m = *scene.render.media[0];
    ASSERT_TRUE(m.motion().transformMoves());
    const Bounds3 world = m.worldBounds();
    Medium::Context ctx(m);
    for (int i = 0; i <= 100; ++i) {
        ctx.setTimeOffset(float(-0.25 + 0.5 * i / 100.0));
        const Bounds3 at = ctx.objectToWorld().apply(m.objectBounds());
        for (const Vec3& c : {at.lo, at.hi})
            for (int a = 0; a < 3; ++a) {
                EXPECT_LE(world.lo[a], c[a] + 1e-5f);
                EXPECT_GE(world.hi[a], c[a] - 1e-5f);
            }
    }
}

TEST(KeyedTransform, InterpolatesThePartsBetweenKeys) {
    TransformParts a, b;
    a.degrees = 10;
    b.degrees = 350;  // same axis: the angle itself is interpolated, past 180°
    a.translate = Vec3d(0, 0, 0);
    b.translate = Vec3d(2, 0, 0);
    b.scale = Vec3d(3, 1, 1);
    KeyedTransform k({TransformKey{1.0, b}, TransformKey{-1.0, a}});
    const TransformParts mid = k.partsAt(0.0);
    EXPECT_DOUBLE_EQ(mid.degrees, 180.0);
    EXPECT_DOUBLE_EQ(mid.translate.x, 1.0);
    EXPECT_DOUBLE_EQ(mid.scale.x, 2.0);
    EXPECT_DOUBLE_EQ(k.partsAt(-5.0).degrees, 10.0);  // held beyond the keys
    EXPECT_DOUBLE_EQ(k.partsAt(5.0).degrees, 350.0);
    // Different axes: the great arc, halfway a 45° turn about the bisector of x and y for
    // 90° about x to 90° about y... here from identity to 90° about z: 45° about z.
    TransformParts c, d;
    c.axis = Vec3d(1, 0, 0);
    d.degrees = 90;
    d.axis = Vec3d(0, 0, 1);
    const TransformParts half =
        KeyedTransform({TransformKey{0, c}, TransformKey{1, d}}).partsAt(0.5);
    EXPECT_NEAR(half.degrees, 45.0, 1e-9);
    EXPECT_NEAR(half.axis.z, 1.0, 1e-9);
    // A key's own time gives its parts' transform, bit for bit.
    EXPECT_TRUE(k.at(1.0).linear.m == b.compose().linear.m);
}

}  // namespace
}  // namespace mirage
