// The render's deliveries beside the beauty, read from [output] (docs/aovs.md): the render
// passes (aovs), checked once the lights and their groups are known, and the deep image.
#pragma once

#include <functional>
#include <string>

#include "scene/scene.h"
#include "scene/toml_reader.h"

namespace mirage {

// [output] deep, deep_alpha_tolerance, deep_color_tolerance into scene->settings.deep; the
// deep path may not be the beauty's (scene->output.path, read before).
void readDeepSettings(const TableReader& output,
                      const std::function<std::string(const std::string&)>& resolve, Scene* scene);

// [output] cryptomatte = ["volume", "shape"]: the Cryptomatte passes (crypto_volume,
// crypto_shape) added to scene->settings.aovs.
void readCryptomatte(const TableReader& output, Scene* scene);

// An object's `name` (Cryptomatte, film/cryptomatte.h), `fallback` when the table has none;
// an error names the line of a name Cryptomatte cannot carry.
std::string readObjectName(const TableReader& object, const std::string& fallback);

// [output] aovs (already in scene.settings.aovs) against the passes the scene has; an error
// names the key's line.
void checkAovs(const TableReader& top, const Scene& scene);

}  // namespace mirage
