// [[light]] tables of a scene file (docs/scene-file.md, "Lights").
#pragma once

#include <memory>

#include "light/light.h"
#include "scene/toml_reader.h"

namespace mirage {

class ColorPipeline;

// One [[light]]; errors name the file, line and key.
std::unique_ptr<Light> readLight(const TableReader& t, const ColorPipeline& color);

}  // namespace mirage
