// How far a point on a surface is pushed off it so that a ray leaving it does not hit that
// surface again: a few ulps of the position's magnitude (float positions have a relative
// precision of 6e-8; 2e-5 leaves a wide margin for the intersection's own rounding). Shared by
// rays spawned at surface hits (geometry), shadow rays kept short of a target on a surface
// (a quad light on a ceiling), and photons leaving an area light that lies on a surface.
#pragma once

#include "core/math.h"

namespace mirage {

inline float surfaceEpsilon(const Vec3& p) {
    const float m = std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z)));
    return 2e-5f * std::max(1.f, m);
}

}  // namespace mirage
