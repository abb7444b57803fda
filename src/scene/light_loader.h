// [[light]] tables of a scene file (docs/scene-file.md, "Lights").
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "light/light.h"
#include "light/surface_light.h"
#include "render/render_scene.h"
#include "scene/toml_reader.h"

namespace mirage {

class ColorPipeline;

// One [[light]]; errors name the file, line and key. `resolve` turns a path written in the scene
// (a dome's `map`) into one relative to the working directory.
std::unique_ptr<Light> readLight(const TableReader& t, const ColorPipeline& color,
                                 const std::function<std::string(const std::string&)>& resolve);
// Every [[light]] of the scene into scene->lights, with its group (`group = "key"`, for the
// lightgroup_* passes) into scene->lightGroups and lightGroupIndex.
void readLights(const TableReader& top, const ColorPipeline& color,
                const std::function<std::string(const std::string&)>& resolve, RenderScene* scene);

// The scene's emissive meshes and quads (readGeometry's `emitters`) as one light after its
// [[light]]s (light/surface_light.h), in the light-group passes' emission slot; nothing when no
// surface emits.
void addSurfaceLight(EmissiveTriangles triangles, RenderScene* scene);

}  // namespace mirage
