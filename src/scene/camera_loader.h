// [camera] as a scene file gives it: the pose, a turntable, and `[[camera.key]]` poses per frame
// that move the camera within the shutter (camera motion blur). The keys are documented in
// docs/scene-file.md, "Camera motion".
#pragma once

#include "render/camera.h"
#include "scene/toml_reader.h"

namespace mirage {

struct Scene;

// [camera] for frame `frame`, or a camera framing the scene's bounds when there is none. The
// scene's settings ([film], [output] fps) and media are read before. The shutter is read
// separately (readShutter, before the volumes) and set by setShutterSeconds.
CameraDesc readCamera(const TableReader& top, int frame, const Scene& scene);

}  // namespace mirage
