// Confinement (medium/confinement.h): where in its box a medium exists. A point is inside when
// it is in the region and in no cut-out; rays are clipped to the region's chord; the medium keeps
// Beer–Lambert's closed form only while every ray meets it in one interval; its world bounds
// shrink to the region's. The media it confines are tested in physics/interior_medium_test.cpp.
#include "medium/confinement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace mirage;

namespace {

// A ball, or a spherical shell (convex: false), as a region.
class Ball : public Region {
public:
    Ball(const Vec3& centre, float radius, bool convex = true)
        : mCentre(centre), mRadius(radius), mConvex(convex) {}
    bool contains(const Vec3& p) const override { return length(p - mCentre) <= mRadius; }
    bool clip(const Ray& ray, float* t0, float* t1) const override {
        // |o + t d − c|² = r² with |d| = 1.
        const Vec3 oc = ray.o - mCentre;
        const float b = dot(oc, ray.d), c = dot(oc, oc) - mRadius * mRadius;
        const float disc = b * b - c;
        if (!(disc >= 0.f)) return false;
        const float s = std::sqrt(disc);
        *t0 = std::max(*t0, -b - s);
        *t1 = std::min(*t1, -b + s);
        return *t0 < *t1;
    }
    bool convex() const override { return mConvex; }
    Bounds3 bounds() const override {
        Bounds3 b;
        b.expand(mCentre - Vec3(mRadius));
        b.expand(mCentre + Vec3(mRadius));
        return b;
    }

private:
    Vec3 mCentre;
    float mRadius;
    bool mConvex;
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
    c.confineTo(std::make_shared<Ball>(Vec3(0.f), 2.f));
    c.excludeFrom(std::make_shared<Ball>(Vec3(1.f, 0.f, 0.f), 0.5f));
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
    c.confineTo(std::make_shared<Ball>(Vec3(0.f), 1.f));
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
    shell.confineTo(std::make_shared<Ball>(Vec3(0.f), 1.f, false));
    EXPECT_FALSE(shell.oneInterval());
}

TEST(Confinement, WorldBoundsShrinkToTheRegion) {
    Confinement c;
    c.confineTo(std::make_shared<Ball>(Vec3(1.f, 0.f, 0.f), 1.f));
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
    far.confineTo(std::make_shared<Ball>(Vec3(10.f), 1.f));
    EXPECT_TRUE(far.clipBounds(box).empty());
    EXPECT_EQ(Confinement().clipBounds(box).lo.x, -1.f);
}
