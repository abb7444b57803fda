// A transform keyed in time: rigid (and scaling) motion of an object within the shutter. Each
// key holds the parts a scene file writes — scale, then a rotation by an angle about an axis,
// then a translation — and the transform at a time between two keys interpolates the parts:
// scale and translation linearly, the rotation along the great arc between the keys' unit
// quaternions (Shoemake 1985, "Animating rotation with quaternion curves"). The arc is taken
// without flipping a quaternion's sign, so keys about one axis turn by the linearly
// interpolated angle, beyond 180° between keys too (up to, not including, 360°).
#pragma once

#include <vector>

#include "core/transform.h"

namespace mirage {

struct TransformParts {
    Vec3d scale{1, 1, 1};
    double degrees = 0;
    Vec3d axis{0, 1, 0};  // unit
    Vec3d translate{0, 0, 0};
    // translate ∘ rotate ∘ scale; a part at its identity is left out, so a transform written
    // with only some parts has the bits it had before keys existed.
    Transform compose() const;
};

struct TransformKey {
    double time = 0;  // seconds relative to the frame
    TransformParts parts;
};

class KeyedTransform {
public:
    KeyedTransform() = default;
    // Keys in any order (sorted here), at distinct times.
    explicit KeyedTransform(std::vector<TransformKey> keys);
    // More than one key: the transform changes with time.
    bool moves() const { return mKeys.size() > 1; }
    bool empty() const { return mKeys.empty(); }
    // The transform at time offset t (seconds), held beyond the first and last keys.
    Transform at(double t) const;
    TransformParts partsAt(double t) const;
    // World bounds of an object-space box over every time in [t0, t1]: the boxes at 64 times
    // (and at the keys within), grown by the farthest a corner moves from one time to the
    // next. Between two times a point stays within that chord of where it was (along a line,
    // or an arc of a turn under 180°), and the box's points are affine mixtures of its corners.
    Bounds3 sweep(const Bounds3& objectBox, double t0, double t1) const;

private:
    std::vector<TransformKey> mKeys;
};

}  // namespace mirage
