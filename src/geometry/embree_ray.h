// One Embree ray query set up the same way everywhere Mirage calls rtcIntersect1 (surfaces,
// shape regions, photon discs): origin, direction, [tnear, tfar], no motion blur, all masks,
// nothing hit yet.
#pragma once

#include <embree3/rtcore.h>

#include "core/math.h"

namespace mirage {

inline RTCRayHit embreeRayHit(const Vec3& o, const Vec3& d, float tNear, float tFar) {
    RTCRayHit rh;
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = tNear;
    rh.ray.tfar = tFar;
    rh.ray.time = 0.f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

}  // namespace mirage
