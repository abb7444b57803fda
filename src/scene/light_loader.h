// [[light]] tables of a scene file (docs/scene-file.md, "Lights").
#pragma once

#include <memory>

#include "light/light.h"
#include "render/render_scene.h"
#include "scene/toml_reader.h"

namespace mirage {

class ColorPipeline;

// One [[light]]; errors name the file, line and key.
std::unique_ptr<Light> readLight(const TableReader& t, const ColorPipeline& color);
// Every [[light]] of the scene into scene->lights, with its group (`group = "key"`, for the
// lightgroup_* passes) into scene->lightGroups and lightGroupIndex.
void readLights(const TableReader& top, const ColorPipeline& color, RenderScene* scene);

}  // namespace mirage
