#include "render/camera.h"

#include <algorithm>

#include "core/transform.h"

namespace mirage {

namespace {

// Piecewise linear between the keys bracketing dt, held beyond the ends. Position and look-at
// move along straight lines between keys; `up` is renormalised by the camera.
CameraPose interpolateKeys(const std::vector<CameraKey>& keys, float dt) {
    if (dt <= keys.front().time) return keys.front().pose;
    if (dt >= keys.back().time) return keys.back().pose;
    auto hi = std::upper_bound(keys.begin(), keys.end(), dt,
                               [](float t, const CameraKey& k) { return t < k.time; });
    const CameraKey& b = *hi;
    const CameraKey& a = *(hi - 1);
    const float u = (dt - a.time) / (b.time - a.time);
    CameraPose p;
    p.position = a.pose.position + (b.pose.position - a.pose.position) * u;
    p.lookAt = a.pose.lookAt + (b.pose.lookAt - a.pose.lookAt) * u;
    p.up = a.pose.up + (b.pose.up - a.pose.up) * u;
    p.fovDeg = lerp(u, a.pose.fovDeg, b.pose.fovDeg);
    return p;
}

}  // namespace

CameraPose orbitCamera(const CameraPose& base, float degrees) {
    // No rotation keeps the pose's bits (a closed shutter renders as a still).
    if (degrees == 0.f) return base;
    CameraPose c = base;
    Transform r = Transform::rotate(degrees, Vec3d(normalize(base.up)));
    c.position = base.lookAt + r.vector(base.position - base.lookAt);
    return c;
}

CameraPose CameraDesc::poseAt(float dt) const {
    if (keys.empty()) return orbitCamera(*this, orbitDegreesPerSecond * dt);
    return orbitCamera(interpolateKeys(keys, dt), orbitDegrees + orbitDegreesPerSecond * dt);
}

void setTurntable(CameraDesc* camera, int frame, int frames, double fps) {
    const int k = ((frame - 1) % frames + frames) % frames;
    camera->orbitDegrees = 360.f * float(k) / float(frames);
    camera->orbitDegreesPerSecond = float(360.0 * fps / double(frames));
    static_cast<CameraPose&>(*camera) = orbitCamera(*camera, camera->orbitDegrees);
}

}  // namespace mirage
