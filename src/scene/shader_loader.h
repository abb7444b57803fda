// Shader files (shaders/*.toml) → ShaderDesc. A shader is found by name — in the scene's
// folder, then in its shaders/ subfolder, then $MIRAGE_SHADER_PATH, then among the shaders
// built into the binary — or by a path ending in .toml.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "medium/shader.h"
#include "scene/toml_reader.h"

namespace mirage {

ShaderDesc loadShader(const std::string& nameOrPath, const std::string& sceneDir);
ShaderDesc parseShader(const toml::table& doc, const std::string& file);
// A spectrum-valued key: a number, an RGB triple (reflectance-style upsampling) or a table
// { wavelengths = [nm…], values = […] }. Values must be ≥ 0.
Spectrum readCoefficientSpectrum(const TableReader& t, const std::string& key, float def);

std::vector<std::string> builtinShaderNames();
// Generated from shaders/*.toml at build time.
const std::vector<std::pair<std::string, const char*>>& builtinShaders();

}  // namespace mirage
