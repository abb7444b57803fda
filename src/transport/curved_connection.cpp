// Connections to lights at infinity along Fermat paths (curved_connection.h says which and why).
#include "transport/curved_connection.h"

#include <cmath>

namespace mirage {

namespace {

// Newton's method on ωe(ωi) = s: iterations, the angle (rad) at which the escape direction
// counts as the target (far below the sun's 4.6e−3 rad, and above the directions' error from
// the stepper's tolerance: a tighter one took a third more walks on the mirage scenes), and
// the finite-difference step of the Jacobian (rad): well above the directions' error from the
// stepper's tolerance (~1e−6 per path), well below the angles over which a layer's focusing
// changes (the flattened sun's 0.19° image of 0.53°: 3e−3 rad).
constexpr int kAimIterations = 8;
constexpr double kAimTolerance = 1e-5;
constexpr float kAimStep = 2e-4f;

// The walk of escapeCurved over one chord: its transmittance where tracked; false (the walk
// ends) once nothing gets through any more.
struct EscapeStep {
    TrackingContext* ctx;
    Sampler* sampler;
    SampledSpectrum* T;
    bool operator()(const CurvedChord& chord, CurvedWalkEnd* end) const {
        if (ctx) *T *= transmittance(*ctx, chord.arcRay, chord.tStop, *sampler);
        if (T->maxValue() > 0.f || chord.surfaceAhead) return true;
        end->kind = CurvedWalkEnd::Kind::Stopped;
        return false;
    }
};

// The escape direction's offset from the target in the plane across it (rad, small angles).
struct Offset {
    double a = 0, b = 0;
    Offset(const Vec3& e, const Vec3& target, const Frame& across) {
        const Vec3 d = e - target;
        a = dot(d, across.s);
        b = dot(d, across.t);
    }
    double size() const { return std::sqrt(a * a + b * b); }
};

// dωe/dωi in the plane across the target, by forward differences from wi (whose escape is at
// e0): column j is the escape's offset per radian of wi turned along the frame's axis j.
struct Jacobian {
    double m[2][2] = {{1, 0}, {0, 1}};
    double det() const { return m[0][0] * m[1][1] - m[0][1] * m[1][0]; }
};

}  // namespace

std::optional<CurvedEscape> escapeCurved(const CurvedWalk& walk, const Ray& start, float lambdaNm,
                                         TrackingContext* ctx, Sampler* sampler) {
    CurvedEscape out;
    out.nStart = walk.field.index(Vec3d(start.o), lambdaNm);
    const CurvedWalkEnd end =
        walkCurvedChords(walk, start, lambdaNm, EscapeStep{ctx, sampler, &out.T});
    using Kind = CurvedWalkEnd::Kind;
    if (end.kind == Kind::Surface || end.kind == Kind::Stopped) return std::nullopt;
    out.direction = end.direction;
    out.nExit = walk.field.index(Vec3d(end.p), lambdaNm);
    if (end.kind != Kind::Left) {
        // Beyond the curved length (or the stepper's cap) inside the scene: straight on.
        const Ray on{end.p, end.direction};
        if (walk.surfaces && walk.surfaces(on, kInfinity) < kInfinity) return std::nullopt;
        if (ctx) out.T *= transmittance(*ctx, on, kInfinity, *sampler);
        if (!(out.T.maxValue() > 0.f)) return std::nullopt;
    }
    return out;
}

std::optional<CurvedAim> aimCurved(const CurvedWalk& walk, const Vec3& origin, const Vec3& target,
                                   float lambdaNm, TrackingContext& ctx, Sampler& sampler) {
    const Frame across(target);
    auto escapeAlong = [&](const Vec3& wi) {
        return escapeCurved(walk, Ray{origin, wi}, lambdaNm);
    };
    // The Jacobian at wi, or nothing when a neighbouring path is blocked (a graze).
    auto jacobianAt = [&](const Vec3& wi, const Offset& r0) -> std::optional<Jacobian> {
        Jacobian J;
        const Vec3 axes[2] = {across.s, across.t};
        for (int j = 0; j < 2; ++j) {
            const auto e = escapeAlong(normalize(wi + axes[j] * kAimStep));
            if (!e) return std::nullopt;
            const Offset r(e->direction, target, across);
            J.m[0][j] = (r.a - r0.a) / double(kAimStep);
            J.m[1][j] = (r.b - r0.b) / double(kAimStep);
        }
        return J;
    };
    Vec3 wi = target, wiJacobian;
    std::optional<Jacobian> J;
    for (int k = 0; k < kAimIterations; ++k) {
        const auto e = escapeCurved(walk, Ray{origin, wi}, lambdaNm, &ctx, &sampler);
        if (!e) return std::nullopt;
        const Offset r(e->direction, target, across);
        // The Jacobian is kept while wi stays within the finite difference's own step of where
        // it was taken (no finer than its resolution), else taken anew.
        if (!J || length(wi - wiJacobian) > kAimStep) {
            J = jacobianAt(wi, r);
            wiJacobian = wi;
            if (!J) return std::nullopt;
        }
        const double det = J->det();
        if (r.size() < kAimTolerance) return CurvedAim{wi, *e, float(std::abs(det))};
        if (!(std::abs(det) > 1e-12)) return std::nullopt;  // a caustic: no finite irradiance
        // Newton's step: J δ = −r.
        const double da = (-r.a * J->m[1][1] + r.b * J->m[0][1]) / det;
        const double db = (-r.b * J->m[0][0] + r.a * J->m[1][0]) / det;
        wi = normalize(wi + across.s * float(da) + across.t * float(db));
    }
    return std::nullopt;
}

}  // namespace mirage
