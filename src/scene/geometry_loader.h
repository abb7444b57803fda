// Scene-file surfaces: [[material]] and [[shape]] tables → GeometryScene
// (docs/scene-file.md, "Surfaces").
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/keyed_transform.h"
#include "core/transform.h"
#include "geometry/geometry_scene.h"
#include "light/surface_light.h"
#include "scene/toml_reader.h"

namespace mirage {

class ColorPipeline;

// Reads every [[material]] and [[shape]] of the top-level table. `resolve` turns a path in the
// file into one relative to the scene's folder; `volumeCount` bounds interior_medium. Returns
// null when the scene has no shape (then a [[material]] table is still checked). `emitters`,
// when given, receives the world triangles of the emissive meshes and quads, by material
// (light/surface_light.h).
std::unique_ptr<GeometryScene> readGeometry(
    const TableReader& top, const std::function<std::string(const std::string&)>& resolve,
    size_t volumeCount, const ColorPipeline& color, EmissiveTriangles* emitters = nullptr);

// { scale, rotate, translate } as for volumes (scene_loader.cpp).
Transform readTransform(const TableReader& t);
// The parts of a `transform` table (scale, rotate, translate), those it leaves out from `def`;
// its other keys are left unread.
TransformParts readTransformParts(const TableReader& t, const TransformParts& def = {});

}  // namespace mirage
