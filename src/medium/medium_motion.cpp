#include "medium/medium_motion.h"

#include <cmath>
#include <utility>

#include "volume/grid_lookup.h"

namespace mirage {

void MediumMotion::setVelocity(VectorGrid velocity, float velocityScale, float maxTimeOffset) {
    mVelocity = std::move(velocity);
    mVelocityScale = velocityScale;
    const double perVelocity = std::abs(double(velocityScale)) * std::abs(double(maxTimeOffset));
    mReachPerVelocity = float(perVelocity);
    mBlurRadius = 0.f;
    if (!mVelocity.valid()) return;
    const double R = double(mVelocity.magnitudeBound()) * perVelocity;
    if (R > 0.0) mBlurRadius = float(R);
}

void MediumMotion::setTransformKeys(KeyedTransform keys, float shutterOpen, float shutterClose) {
    mKeys = std::move(keys);
    mShutterOpen = shutterOpen;
    mShutterClose = shutterClose;
}

Bounds3 MediumMotion::sweep(const Bounds3& objectBounds, const Transform& objectToWorld) const {
    return mKeys.moves() ? mKeys.sweep(objectBounds, mShutterOpen, mShutterClose)
                         : objectToWorld.apply(objectBounds);
}

MediumMotion::Path::Path(const MediumMotion& motion, const Transform& objectToWorld,
                         const Transform& worldToObject)
    : mMotion(&motion), mObjectToWorld(objectToWorld), mWorldToObject(worldToObject) {
    if (motion.mVelocity.valid())
        mVelocityAcc = std::make_unique<VectorGrid::Accessor>(motion.mVelocity.accessor());
}

MediumMotion::Path::Path(Path&&) noexcept = default;
MediumMotion::Path& MediumMotion::Path::operator=(Path&&) noexcept = default;
MediumMotion::Path::~Path() = default;

Vec3 MediumMotion::Path::displacement(const Vec3& p) {
    if (mTime == 0.f) return Vec3(0.f);
    return mMotion->mVelocity.sample(*mVelocityAcc, p) * (mMotion->mVelocityScale * mTime);
}

void MediumMotion::Path::placeAt(float seconds) {
    mObjectToWorld = mMotion->mKeys.at(seconds);
    mWorldToObject = mObjectToWorld.inverse();
}

}  // namespace mirage
