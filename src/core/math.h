// Small vector maths shared by every stage: 3-vectors, orthonormal frames, constants.
// Float precision throughout the hot paths; world coordinates are metres.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mirage {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv4Pi = 0.07957747154594766788f;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

template <typename T>
struct Vec3T {
    T x = 0, y = 0, z = 0;
    constexpr Vec3T() = default;
    constexpr Vec3T(T a, T b, T c) : x(a), y(b), z(c) {}
    constexpr explicit Vec3T(T v) : x(v), y(v), z(v) {}
    template <typename U>
    constexpr explicit Vec3T(const Vec3T<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

    constexpr T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    T& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3T operator+(const Vec3T& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3T operator-(const Vec3T& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3T operator*(const Vec3T& o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3T operator/(const Vec3T& o) const { return {x / o.x, y / o.y, z / o.z}; }
    constexpr Vec3T operator*(T s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3T operator/(T s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3T operator-() const { return {-x, -y, -z}; }
    Vec3T& operator+=(const Vec3T& o) { x += o.x; y += o.y; z += o.z; return *this; }
    Vec3T& operator-=(const Vec3T& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    Vec3T& operator*=(T s) { x *= s; y *= s; z *= s; return *this; }
    constexpr bool operator==(const Vec3T& o) const { return x == o.x && y == o.y && z == o.z; }
    constexpr bool operator!=(const Vec3T& o) const { return !(*this == o); }
};

using Vec3 = Vec3T<float>;
using Vec3d = Vec3T<double>;

template <typename T>
constexpr Vec3T<T> operator*(T s, const Vec3T<T>& v) { return v * s; }
template <typename T>
constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <typename T>
constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
inline T length(const Vec3T<T>& v) { return std::sqrt(dot(v, v)); }
template <typename T>
inline Vec3T<T> normalize(const Vec3T<T>& v) { return v / length(v); }
template <typename T>
constexpr Vec3T<T> vmin(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <typename T>
constexpr Vec3T<T> vmax(const Vec3T<T>& a, const Vec3T<T>& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <typename T>
inline bool isFinite(const Vec3T<T>& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <typename T>
constexpr T clamp(T v, T lo, T hi) { return v < lo ? lo : (v > hi ? hi : v); }
template <typename T>
constexpr T lerp(T t, T a, T b) { return (1 - t) * a + t * b; }
inline float safeSqrt(float x) { return std::sqrt(std::max(0.f, x)); }
inline float radians(float deg) { return deg * (kPi / 180.f); }

// Orthonormal basis around a unit vector n (Duff et al. 2017, "Building an orthonormal basis,
// revisited": branchless, no singularity except the sign switch at n.z = 0).
struct Frame {
    Vec3 s, t, n;
    Frame() = default;
    explicit Frame(const Vec3& normal) : n(normal) {
        float sign = std::copysign(1.f, n.z);
        float a = -1.f / (sign + n.z);
        float b = n.x * n.y * a;
        s = Vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3(b, sign + n.y * n.y * a, -n.y);
    }
    Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
    Vec3 toLocal(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

// Axis-aligned box in world space (metres).
struct Bounds3 {
    Vec3 lo{kInfinity}, hi{-kInfinity};
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void expand(const Vec3& p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    void expand(const Bounds3& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    Vec3 diagonal() const { return hi - lo; }
    // Inside or on the faces; false for a NaN coordinate.
    bool contains(const Vec3& p) const {
        return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y &&
               p.z <= hi.z;
    }
    // Slab test; returns false when the ray misses [tMin, tMax].
    bool intersect(const Vec3& o, const Vec3& d, float tMin, float tMax, float* t0,
                   float* t1) const {
        for (int a = 0; a < 3; ++a) {
            float inv = 1.f / d[a];
            float tn = (lo[a] - o[a]) * inv, tf = (hi[a] - o[a]) * inv;
            if (tn > tf) std::swap(tn, tf);
            tMin = tn > tMin ? tn : tMin;  // NaN-safe: a NaN tn leaves tMin unchanged
            tMax = tf < tMax ? tf : tMax;
            if (tMin > tMax) return false;
        }
        *t0 = tMin;
        *t1 = tMax;
        return true;
    }
};

struct Ray {
    Vec3 o, d;  // origin (m), unit direction
    float tMax = kInfinity;
    Vec3 at(float t) const { return o + d * t; }
};

}  // namespace mirage
