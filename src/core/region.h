// A closed region of space: the inside of a closed surface (a glass sphere, a water tank) that
// bounds a medium. The geometry stage implements it for its closed shapes; media and transport
// only ask it these questions, so neither depends on the surfaces.
#pragma once

#include "core/math.h"

namespace mirage {

class Region {
public:
    virtual ~Region() = default;
    // True when the world point lies inside.
    virtual bool contains(const Vec3& p) const = 0;
    // Narrows [*t0, *t1] (parameters of `ray`, world metres) to the part inside: exactly for a
    // convex region; otherwise to the span from the first entry to the last exit, within which
    // contains() decides. Returns false when the ray misses the region within [*t0, *t1].
    virtual bool clip(const Ray& ray, float* t0, float* t1) const = 0;
    // Every straight line crosses the region in at most one interval.
    virtual bool convex() const = 0;
    virtual Bounds3 bounds() const = 0;
};

}  // namespace mirage
