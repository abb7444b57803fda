#include "core/keyed_transform.h"

#include <algorithm>
#include <cmath>

namespace mirage {

namespace {

struct Quat {
    double w, x, y, z;
};

Quat fromAxisAngle(double degrees, const Vec3d& axis) {
    const double h = 0.5 * degrees * 3.14159265358979323846 / 180.0;
    const double s = std::sin(h);
    return {std::cos(h), axis.x * s, axis.y * s, axis.z * s};
}

// Slerp without the sign flip (see the header): the arc from a to b through angle Ω, where
// cos Ω = a·b; a and b antipodal (a 360° turn between keys) has no unique arc.
Quat slerp(const Quat& a, const Quat& b, double u) {
    const double c = std::clamp(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z, -1.0, 1.0);
    const double omega = std::acos(c);
    double ka = 1.0 - u, kb = u;
    if (omega > 1e-9) {
        ka = std::sin((1.0 - u) * omega) / std::sin(omega);
        kb = std::sin(u * omega) / std::sin(omega);
    }
    return {ka * a.w + kb * b.w, ka * a.x + kb * b.x, ka * a.y + kb * b.y, ka * a.z + kb * b.z};
}

bool sameAxis(const Vec3d& a, const Vec3d& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

Vec3d lerpVec(double u, const Vec3d& a, const Vec3d& b) { return a + (b - a) * u; }

}  // namespace

Transform TransformParts::compose() const {
    Transform xf;
    if (!(scale.x == 1 && scale.y == 1 && scale.z == 1)) xf = Transform::scale(scale) * xf;
    if (degrees != 0) xf = Transform::rotate(degrees, axis) * xf;
    if (!(translate.x == 0 && translate.y == 0 && translate.z == 0))
        xf = Transform::translate(translate) * xf;
    return xf;
}

KeyedTransform::KeyedTransform(std::vector<TransformKey> keys) : mKeys(std::move(keys)) {
    std::sort(mKeys.begin(), mKeys.end(),
              [](const TransformKey& a, const TransformKey& b) { return a.time < b.time; });
}

TransformParts KeyedTransform::partsAt(double t) const {
    if (mKeys.empty()) return TransformParts();
    if (t <= mKeys.front().time) return mKeys.front().parts;
    if (t >= mKeys.back().time) return mKeys.back().parts;
    auto hi = std::upper_bound(mKeys.begin(), mKeys.end(), t,
                               [](double v, const TransformKey& k) { return v < k.time; });
    const TransformParts& a = (hi - 1)->parts;
    const TransformParts& b = hi->parts;
    const double u = (t - (hi - 1)->time) / (hi->time - (hi - 1)->time);
    TransformParts p;
    p.scale = lerpVec(u, a.scale, b.scale);
    p.translate = lerpVec(u, a.translate, b.translate);
    if (sameAxis(a.axis, b.axis)) {
        p.axis = a.axis;
        p.degrees = a.degrees + (b.degrees - a.degrees) * u;
    } else {
        const Quat q = slerp(fromAxisAngle(a.degrees, a.axis), fromAxisAngle(b.degrees, b.axis), u);
        const double s = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
        p.degrees = s > 0 ? 2.0 * std::atan2(s, q.w) * 180.0 / 3.14159265358979323846 : 0.0;
        p.axis = s > 0 ? Vec3d(q.x / s, q.y / s, q.z / s) : a.axis;
    }
    return p;
}

Transform KeyedTransform::at(double t) const { return partsAt(t).compose(); }

Bounds3 KeyedTransform::sweep(const Bounds3& box, double t0, double t1) const {
    std::vector<double> times;
    constexpr int kSteps = 64;
    for (int i = 0; i <= kSteps; ++i) times.push_back(t0 + (t1 - t0) * i / kSteps);
    for (const TransformKey& k : mKeys)
        if (k.time > t0 && k.time < t1) times.push_back(k.time);
    std::sort(times.begin(), times.end());
    auto corner = [&](int c) {
        return Vec3(c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                    c & 4 ? box.hi.z : box.lo.z);
    };
    Bounds3 out;
    float grow = 0.f;
    Transform prev = at(times.front());
    for (double t : times) {
        const Transform xf = at(t);
        out.expand(xf.apply(box));
        for (int c = 0; c < 8; ++c)
            grow = std::max(grow, length(xf.point(corner(c)) - prev.point(corner(c))));
        prev = xf;
    }
    out.lo = out.lo - Vec3(grow);
    out.hi = out.hi + Vec3(grow);
    return out;
}

}  // namespace mirage
