// The step cap near surfaces, the rule that sets
// CurvedPathSettings::stepCap when a scene has surfaces.
//
// Every accepted step is a chord, and a surface hit is found on the chord: a chord of length h
// on a path of curvature κ ≤ |∇n|/n stands off the path by up to its sagitta κh²/8, and where it
// crosses a surface at the angle α its hit is up to sagitta/sin α from the path's. Left to the
// error controller alone, steps grow to metres (or to max_step) where the field is smooth, so a
// path meeting a surface at a shallow angle, or grazing it, is cut by a long chord: a hit metres
// away from the true one, or a graze missed (a chord under a convex arc misses a surface that
// the arc touches).
//
// The rule: with t the distance to the first surface along the path's current tangent and
//     h_floor = sqrt(8·tolerance·n/|∇n|)   (a chord this long stands off the path by at most the
//                                            stepper's tolerance),
// the next step is at most t − h_floor/2 when t > h_floor, else h_floor. Far from surfaces the
// cap is far above any step the controller takes. Nearing a surface the path turns away from its
// tangent, which meets the surface first when the path bends away from it (grazing, or a ray
// curving up over a hot road): each step then ends short of the surface and the next tangent
// distance shrinks quadratically (the path falls short by κt²/2), until the chord that crosses
// is h_floor long: its hit lies within tolerance/sin α of the path's, and a graze deeper than
// the tolerance is not missed. Stopping h_floor/2 short, not at the tangent's crossing, keeps a
// straight-ish path from ending a step on the surface itself, where rounding could carry the
// next chord's start through it.
//
// What it does not bound: a path bending towards a surface meets it before its tangent does, so
// the crossing chord can be as long as the tangent distance allows; there max_step bounds the
// error (sagitta of max_step / sin α).
//
// Cost: one ray query against the surfaces and one field evaluation per trial step of the path
// (docs/curved-light.md, "Curved light in scenes", gives the measured cost).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "medium/index_field.h"
#include "transport/curved_path.h"

namespace mirage {

// Distance (m) from origin along the unit direction to the first surface, +∞ for none.
using SurfaceDistance = std::function<double(const Vec3d& origin, const Vec3d& direction)>;

// The step cap of the rule above for `field` (kept alive by the caller) and the stepper's
// tolerance. The floor uses n and ∇n at 550 nm: dispersion changes it by ~1e−4 of itself.
inline std::function<double(const Vec3d&, const Vec3d&)> surfaceStepCap(
    const IndexField* field, double tolerance, SurfaceDistance distance) {
    return [field, tolerance, distance = std::move(distance)](const Vec3d& r, const Vec3d& d) {
        const double t = distance(r, d);
        if (!(t < std::numeric_limits<double>::infinity())) return 0.0;  // nothing ahead: no cap
        double n;
        Vec3d g;
        field->eval(r, 550.0, &n, &g);
        const double gradient = length(g);
        if (!(gradient > 0.0) || !(n > 0.0)) return 0.0;  // a straight stretch: no sagitta
        const double floor = std::sqrt(8.0 * tolerance * n / gradient);
        return t > floor ? t - 0.5 * floor : floor;
    };
}

}  // namespace mirage
