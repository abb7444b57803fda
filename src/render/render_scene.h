// What the render stage needs of a scene: camera, lights and media, already built. The scene
// stage assembles it; render/ knows nothing of scene files.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "film/aov.h"
#include "geometry/geometry_scene.h"
#include "light/light.h"
#include "medium/medium.h"
#include "render/camera.h"

namespace mirage {

struct RenderScene {
    CameraDesc camera;
    std::vector<std::unique_ptr<Light>> lights;
    std::vector<std::unique_ptr<Medium>> media;
    // Per medium, whether it is a holdout ([[volume]] holdout = true): it attenuates and
    // shadows, but the camera sees no light of its own and no coverage of its own (docs/aovs.md,
    // "Holdouts"). What the output shows, not what the medium is; empty: no holdouts.
    std::vector<bool> mediumHoldouts;
    // Surfaces (meshes, spheres, quads) and their materials; null when the scene has none, and
    // then every integrator behaves exactly as for media alone.
    std::unique_ptr<GeometryScene> geometry;
    // Light groups (the lightgroup_* passes, film/aov.h): their names, and each light's group
    // as an index into them. A light without a group (and every light of a scene that names
    // none) is in the group "default".
    // What Cryptomatte calls the volumes and shapes ([[volume]] and [[shape]] name).
    CryptoObjects cryptoObjects;
    std::vector<std::string> lightGroups;
    std::vector<int> lightGroupIndex;  // per light; empty: all in "default"

    std::vector<std::string> lightGroupNames() const {
        return lightGroups.empty() ? std::vector<std::string>{"default"} : lightGroups;
    }
    // The light's slot among the light-group passes (slot 0 is emission).
    int lightGroupSlot(size_t light) const {
        return light < lightGroupIndex.size() ? lightGroupIndex[light] + 1 : 1;
    }

    // Whether paths draw distances towards point and spot lights besides delta tracking's
    // ([render] lamp_sampling, render/lamp_sampling.h).
    bool equiangular = true;
    // Whether volpath's medium vertices sample the emissive media as a light, by line
    // integration ([render] emission_sampling, render/line_emission.h).
    bool emissionSampling = true;
    // Whether volpath's vertices draw the lights at infinity at a rate from where a sky's sun is
    // hidden (render/sun_shade.h) rather than by the path's last draw alone; false only in tests,
    // which compare the two.
    bool sunShade = true;

    bool hasSurfaces() const { return geometry && !geometry->empty(); }
    bool holdout(size_t medium) const {
        return medium < mediumHoldouts.size() && mediumHoldouts[medium];
    }

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
