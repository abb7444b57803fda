// Confinement (medium/confinement.h): where in its box a medium exists. A point is inside when
// it is in the region and in no cut-out; rays are clipped to the region's chord; the medium keeps
// Beer–Lambert's closed form only while every ray meets it in one interval; its world bounds
// shrink to the region's. The media it confines are tested in physics/interior_medium_test.cpp.
#include "medium/confinement.h"

#include <gtest/gtest.h>

#include <memory>
#include <utility>

#include "geometry/shape_region.h"

using namespace mirage;

namespace {

// The balls are geometry/shape_region.h's sphere regions. This one answers as the region it
// wraps but says it is not convex (a spherical shell's), so that a line may cross it twice.
class NotConvex : public Region {
public:
    explicit NotConvex(std::shared_ptr<const Region> r) : mRegion(std::move(r)) {}
    bool contains(const Vec3& p) const override { return mRegion->contains(p); }
    bool clip(const Ray& ray, float* t0, float* t1) const override {
        return mRegion->clip(ray, t0, t1);
    }
    bool convex() const override { return false; }
    Bounds3 bounds() const override { return mRegion->bounds(); }

private:
    std::shared_ptr<const Region> mRegion;
};

}  // namespace

TEST(Confinement, UnconfinedHoldsEveryPointAndEveryRay) {
    const Confinement everywhere;
    EXPECT_FALSE(everywhere.confines());
    EXPECT_TRUE(everywhere.oneInterval());
    EXPECT_TRUE(everywhere.contains(Vec3(1e6f, -3.f, 0.f)));
    float t0 = 0.5f, t1 = 7.f;
    EXPECT_TRUE(everywhere.clip(Ray{Vec3(0.f), Vec3(1.f, 0.f, 0.f), kInfinity}, &t0, &t1));
    EXPECT_EQ(t0, 0.5f);
    EXPECT_EQ(t1, 7.f);
}

TEST(Confinement, InsideTheRegionAndOutsideEveryCutOut) {
    Confinement c;
    c.confineTo(makeSphereRegion(Vec3(0.f), 2.f));
    c.excludeFrom(makeSphereRegion(Vec3(1.f, 0.f, 0.f), 0.5f));
    c.excludeFrom(nullptr);  // nothing to cut out
    EXPECT_TRUE(c.confines());
    EXPECT_EQ(c.excluded().size(), 1u);
    EXPECT_TRUE(c.contains(Vec3(-1.f, 0.f, 0.f)));
    EXPECT_FALSE(c.contains(Vec3(1.f, 0.f, 0.f)));  // cut out
    EXPECT_FALSE(c.contains(Vec3(3.f, 0.f, 0.f)));  // outside the region
    // A cut-out splits rays into two intervals: no closed form.
    EXPECT_FALSE(c.oneInterval());
}

TEST(Confinement, RaysTakeTheRegionsChord) {
    Confinement c;
    c.confineTo(makeSphereRegion(Vec3(0.f), 1.f));
    EXPECT_TRUE(c.oneInterval());
    const Ray ray{Vec3(-5.f, 0.f, 0.f), Vec3(1.f, 0.f, 0.f), kInfinity};
    float t0 = 0.f, t1 = 100.f;
    ASSERT_TRUE(c.clip(ray, &t0, &t1));
    EXPECT_FLOAT_EQ(t0, 4.f);
    EXPECT_FLOAT_EQ(t1, 6.f);
    float u0 = 0.f, u1 = 3.f;  // ends before the ball
    EXPECT_FALSE(c.clip(ray, &u0, &u1));
    // A region a line may cross twice: the span from first entry to last exit, no closed form.
    Confinement shell;
    shell.confineTo(std::make_shared<NotConvex>(makeSphereRegion(Vec3(0.f), 1.f)));
    EXPECT_FALSE(shell.oneInterval());
}

TEST(Confinement, WorldBoundsShrinkToTheRegion) {
    Confinement c;
    c.confineTo(makeSphereRegion(Vec3(1.f, 0.f, 0.f), 1.f));
    Bounds3 box;
    box.expand(Vec3(-1.f));
    box.expand(Vec3(1.f));
    const Bounds3 b = c.clipBounds(box);
    EXPECT_EQ(b.lo.x, 0.f);
    EXPECT_EQ(b.hi.x, 1.f);
    EXPECT_EQ(b.lo.y, -1.f);
    EXPECT_EQ(b.hi.z, 1.f);
    // No overlap: empty, the medium is nowhere.
    Confinement far;
    far.confineTo(makeSphereRegion(Vec3(10.f), 1.f));
    EXPECT_TRUE(far.clipBounds(box).empty());
    EXPECT_EQ(Confinement().clipBounds(box).lo.x, -1.f);
}
