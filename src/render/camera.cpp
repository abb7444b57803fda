#include "render/camera.h"

#include "core/transform.h"

namespace mirage {

CameraDesc orbitCamera(const CameraDesc& base, float degrees) {
    CameraDesc c = base;
    Transform r = Transform::rotate(degrees, Vec3d(normalize(base.up)));
    c.position = base.lookAt + r.vector(base.position - base.lookAt);
    return c;
}

}  // namespace mirage
