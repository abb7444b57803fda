// Affine transforms (object → world). A volume's grid carries its own index → object map;
// the scene may place the object in the world with this transform (translate, rotate, scale;
// non-uniform and negative-determinant transforms are allowed).
#pragma once

#include "core/math.h"
#include "core/matrix.h"

namespace mirage {

struct Transform {
    Mat3 linear;         // identity by default
    Vec3d translation;   // metres

    Vec3 point(const Vec3& p) const { return Vec3(linear.apply(Vec3d(p)) + translation); }
    Vec3 vector(const Vec3& v) const { return linear.apply(v); }
    Transform inverse() const {
        Transform r;
        r.linear = linear.inverse();
        r.translation = -(r.linear.apply(translation));
        return r;
    }
    Transform operator*(const Transform& o) const {  // (this ∘ o)(p) = this(o(p))
        Transform r;
        r.linear = linear * o.linear;
        r.translation = linear.apply(o.translation) + translation;
        return r;
    }
    bool isIdentity() const {
        return linear.m == Mat3().m && translation == Vec3d();
    }
    Bounds3 apply(const Bounds3& b) const {
        Bounds3 r;
        if (b.empty()) return r;
        for (int i = 0; i < 8; ++i)
            r.expand(point(Vec3(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y,
                                i & 4 ? b.hi.z : b.lo.z)));
        return r;
    }

    static Transform translate(const Vec3d& t) { Transform r; r.translation = t; return r; }
    static Transform scale(const Vec3d& s) {
        Transform r;
        r.linear.m = {s.x, 0, 0, 0, s.y, 0, 0, 0, s.z};
        return r;
    }
    // Rotation by angle (degrees) about a unit axis (Rodrigues' formula).
    static Transform rotate(double degrees, Vec3d axis) {
        axis = normalize(axis);
        double a = degrees * 3.14159265358979323846 / 180.0, c = std::cos(a), s = std::sin(a);
        double x = axis.x, y = axis.y, z = axis.z;
        Transform r;
        r.linear.m = {c + x * x * (1 - c),     x * y * (1 - c) - z * s, x * z * (1 - c) + y * s,
                      y * x * (1 - c) + z * s, c + y * y * (1 - c),     y * z * (1 - c) - x * s,
                      z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)};
        return r;
    }
};

}  // namespace mirage
