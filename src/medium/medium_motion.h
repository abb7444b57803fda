// How a medium moves within the shutter (docs/design.md, "Time"; docs/scene-file.md, "Motion
// blur"): along its velocity field, each lookup advected back along it, and rigidly, by keyed
// transforms. The scene loader builds one (scene/motion_loader.cpp), the medium owns it
// (Medium::setMotion: the majorant and world bounds then cover every time in the shutter), and
// each path consults it through its MediumMotion::Path, which holds the path's time, the
// velocity accessor and the transforms at that time.
#pragma once

#include <memory>

#include "core/keyed_transform.h"
#include "core/math.h"
#include "core/transform.h"
#include "volume/vector_grid.h"

namespace mirage {

class MediumMotion {
public:
    // A still medium: no velocity, and the transform it was built with at every time.
    MediumMotion() = default;

    // Velocity motion blur. The medium at time t₀ + Δt is the still medium advected by its
    // velocity field v (object-space metres per second, times velocityScale) to first order,
    // backward (Kim & Ko 2007, semi-Lagrangian): every grid the shader reads is looked up at
    // x − v(x)·Δt instead of x. maxTimeOffset (seconds) is the largest |Δt| a path may carry
    // (the shutter's reach from the frame). R = max|v|·|velocityScale|·maxTimeOffset = 0 leaves
    // the medium as it was.
    void setVelocity(VectorGrid velocity, float velocityScale, float maxTimeOffset);
    // Rigid motion of the whole volume within the shutter (`[[volume.transform.key]]`): at time
    // offset Δt its object-to-world transform is keys.at(Δt) (core/keyed_transform.h). A path
    // has one time, so along it the volume stands still and its rays stay straight in object
    // space: each lookup is the still volume's, in the frame the path's time places it in, and
    // the object-space majorant bounds it at every time. The world bounds grow to what the
    // volume sweeps over [shutterOpen, shutterClose] (seconds). The medium's own transform is
    // the one at Δt = 0.
    void setTransformKeys(KeyedTransform keys, float shutterOpen, float shutterClose);

    const VectorGrid& velocity() const { return mVelocity; }
    float velocityScale() const { return mVelocityScale; }
    // Whether lookups move with time (a velocity grid and a non-zero displacement bound).
    bool moving() const { return mBlurRadius > 0.f; }
    // R above: the longest displacement a lookup can make (object-space metres).
    float blurRadius() const { return mBlurRadius; }
    // |velocityScale|·maxTimeOffset (seconds): a velocity bound (m/s) times it bounds the
    // displacement.
    float reachPerVelocity() const { return mReachPerVelocity; }
    bool transformMoves() const { return mKeys.moves(); }
    const KeyedTransform& transformKeys() const { return mKeys; }
    // The world box that an object box covers over the shutter, placed by `objectToWorld` when
    // no keys move it.
    Bounds3 sweep(const Bounds3& objectBounds, const Transform& objectToWorld) const;

    // One path's view of the motion.
    class Path;

private:
    VectorGrid mVelocity;
    float mVelocityScale = 1.f, mBlurRadius = 0.f, mReachPerVelocity = 0.f;
    KeyedTransform mKeys;
    float mShutterOpen = 0.f, mShutterClose = 0.f;  // seconds: what the world bounds cover
};

class MediumMotion::Path {
public:
    // A path at the frame's time, the medium placed by its transform at Δt = 0 (and its
    // inverse).
    Path(const MediumMotion& motion, const Transform& objectToWorld,
         const Transform& worldToObject);
    // Out of line: the velocity accessor is NanoVDB's type (volume/grid_lookup.h).
    Path(Path&&) noexcept;
    Path& operator=(Path&&) noexcept;
    ~Path();

    // The path's time relative to the frame, Δt = t − t₀ (seconds): lookups of a moving
    // medium are advected by it. Ignored (kept 0) by a medium that does not move, so a
    // still medium makes exactly the lookups it makes without motion blur.
    // A volume whose transform is keyed moves to where it is at that time.
    void setTimeOffset(float seconds) {
        mPathTime = seconds;
        mTime = mMotion->moving() ? seconds : 0.f;
        if (mMotion->transformMoves()) placeAt(seconds);
    }
    float timeOffset() const { return mPathTime; }
    // The volume's transforms at the path's time.
    const Transform& objectToWorld() const { return mObjectToWorld; }
    const Transform& worldToObject() const { return mWorldToObject; }

    // How far the flow carries the medium at object-space point p over the path's time
    // offset, v(p)·velocityScale·Δt (object metres); 0 for a still path.
    Vec3 displacement(const Vec3& p);
    // The object-space point whose still grids hold the medium at p at the path's time:
    // p itself when the path is still, else p − v(p)·velocityScale·Δt.
    Vec3 lookupPoint(const Vec3& p) {
        if (mTime == 0.f) return p;
        return p - displacement(p);
    }

private:
    void placeAt(float seconds);

    const MediumMotion* mMotion;
    Transform mObjectToWorld, mWorldToObject;
    std::unique_ptr<VectorGrid::Accessor> mVelocityAcc;  // null without a velocity grid
    float mPathTime = 0.f;                               // as set
    float mTime = 0.f;  // the advection's Δt: 0 when the medium has no velocity
};

}  // namespace mirage
