#include "scene/camera_loader.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "scene/motion_loader.h"
#include "scene/scene.h"

namespace mirage {

namespace {

// A pose that can be drawn: the camera does not look at itself and `up` is not the view axis.
void checkPose(const TableReader& t, const CameraPose& p) {
    if (!(length(p.lookAt - p.position) > 0))
        t.fail("look_at", "the camera looks at its own position");
    if (!(length(cross(p.lookAt - p.position, p.up)) > 0))
        t.fail("up", "'up' is parallel to the viewing direction");
}

// One member of a pose: the key's own value, else the [camera] table's, else `def` (nullopt:
// required).
Vec3 poseVector(const TableReader& key, const TableReader& camera, const std::string& name,
                std::optional<Vec3> def) {
    if (key.has(name)) return key.getVec3(name);
    if (camera.has(name) || !def) return camera.getVec3(name);
    return *def;
}

// `[[camera.key]]`: each key a frame and the members of the pose that it sets (the others are
// the [camera] table's). Times are seconds from `frame` at `fps`; keys sorted by frame.
std::vector<CameraKey> readCameraKeys(const TableReader& c, int frame, double fps) {
    std::vector<CameraKey> keys;
    std::vector<double> frames;
    for (const TableReader& k : c.tables("key")) {
        const double f = k.getNumber("frame", 0.0, -1e9, 1e9);
        if (!k.has("frame")) k.fail("frame", "a camera key needs the frame it holds at");
        if (std::find(frames.begin(), frames.end(), f) != frames.end())
            k.fail("frame", "two camera keys at the same frame");
        CameraKey key;
        key.time = float((f - double(frame)) / fps);
        key.pose.position = poseVector(k, c, "position", std::nullopt);
        key.pose.lookAt = poseVector(k, c, "look_at", std::nullopt);
        key.pose.up = poseVector(k, c, "up", Vec3(0, 1, 0));
        key.pose.fovDeg = float(k.has("fov") ? k.getNumber("fov", 40, 0.01, 179)
                                             : c.getNumber("fov", 40, 0.01, 179));
        checkPose(k, key.pose);
        k.finish();
        frames.push_back(f);
        keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end(),
              [](const CameraKey& a, const CameraKey& b) { return a.time < b.time; });
    return keys;
}

}  // namespace

CameraDesc readCamera(const TableReader& top, int frame, const Scene& scene) {
    float aspect = float(scene.settings.width) / float(scene.settings.height);
    auto c = top.optionalTable("camera");
    if (!c) {
        if (!scene.render.media.empty() || scene.render.hasSurfaces())
            return frameBounds(scene.render.bounds(), 40.f, aspect);
        return scene.render.camera;
    }
    CameraDesc cam;
    cam.keys = readCameraKeys(*c, frame, scene.output.fps);
    if (cam.keys.empty()) {
        cam.position = c->getVec3("position");
        cam.lookAt = c->getVec3("look_at");
        cam.up = c->getVec3("up", Vec3(0, 1, 0));
        cam.fovDeg = float(c->getNumber("fov", 40, 0.01, 179));
        checkPose(*c, cam);
    } else {
        // The frame's own pose; the keys give every other time in the shutter.
        static_cast<CameraPose&>(cam) = cam.poseAt(0.f);
        for (const char* k : {"position", "look_at", "up", "fov"}) c->node(k);
    }
    // A turntable: N frames per orbit about `up` through look_at, frame 1 where the camera
    // stands, so `--frames 1-N` renders one full turn (and frame N + 1 is frame 1 again); the
    // orbit goes on turning within the shutter.
    if (c->has("turntable"))
        setTurntable(&cam, frame, int(c->getInt("turntable", 1, 1, 1000000)), scene.output.fps);
    readShutter(*c);  // read before the volumes (loadScene); here so that finish() knows it
    c->finish();
    return cam;
}

}  // namespace mirage
