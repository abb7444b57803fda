// What the render stage needs of a scene: camera, lights and media, already built. The scene
// stage assembles it; render/ knows nothing of scene files.
#pragma once

#include <memory>
#include <vector>

#include "geometry/geometry_scene.h"
#include "light/light.h"
#include "medium/medium.h"
#include "render/camera.h"

namespace mirage {

struct RenderScene {
    CameraDesc camera;
    std::vector<std::unique_ptr<Light>> lights;
    std::vector<std::unique_ptr<Medium>> media;
    // Surfaces (meshes, spheres, quads) and their materials; null when the scene has none, and
    // then every integrator behaves exactly as for media alone.
    std::unique_ptr<GeometryScene> geometry;

    bool hasSurfaces() const { return geometry && !geometry->empty(); }

    std::vector<const Medium*> mediaPointers() const {
        std::vector<const Medium*> r;
        for (const auto& m : media) r.push_back(m.get());
        return r;
    }
    Bounds3 bounds() const {
        Bounds3 b;
        for (const auto& m : media) b.expand(m->worldBounds());
        if (hasSurfaces()) b.expand(geometry->bounds());
        return b;
    }
};

}  // namespace mirage
