// A bare VDB (`mirage render FILE.vdb`) bound as a pyro cache arrives from Houdini or Blender:
// density scatters (the smoke shader), and a fire's temperature, heat and flame grids drive
// the built-in fire shader's blackbody emission. What each grid was bound to, and why, goes to
// `mirage info` (VolumeRecord::notes); docs/cli.md, "A bare VDB", lists the rules.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "medium/shader.h"

namespace mirage {

struct PyroBinding {
    std::string shader = "smoke";                           // "smoke" or "fire"
    std::vector<std::pair<std::string, std::string>> bind;  // shader slot → grid
    bool flame = false;  // fire: the cache has a flame grid for the shader's flame component
    // The cache's temperature units to kelvin: T = scale · value + offset.
    float temperatureScale = 1.f, temperatureOffset = 0.f;
    std::vector<std::string> notes;  // one line per decision, for `mirage info`
};

// Relative temperatures (Houdini's and Mantaflow's: ambient 0, burning ~1–2) as kelvin: the
// ambient at 300 K, one unit 1000 K hotter, so 1.5 glows at 1800 K like the fire shader's
// flame core. A flame grid (reaction progress 0–1) as temperature: 300 K to 1800 K.
constexpr float kAmbientKelvin = 300.f;
constexpr float kKelvinPerRelativeUnit = 1000.f;
constexpr float kFlameKelvinRange = 1500.f;
// A temperature grid whose largest value is above this is taken to be in kelvin already.
constexpr float kKelvinThreshold = 100.f;
// Without a flame grid, a temperature in kelvin makes a fire only from this hot up: cooler
// smoke barely glows (B(λ, 1000 K) in the visible is ~1e-3 of its 1500 K value), and a smoke
// cache's warm air (make-asset smoke's 300–900 K) is its buoyancy or heat haze.
constexpr float kGlowKelvin = 1000.f;

// The largest value of one of the file's scalar grids.
using GridMaximum = std::function<float(const std::string& grid)>;

// The binding of a file whose grids are `grids` (in file order; unnamed as "#N"); maxValue is
// asked for a temperature or heat grid only.
PyroBinding bindPyroCache(const std::vector<std::string>& grids, const GridMaximum& maxValue);

// The fire shader as the binding asks for it: without its flame component when the cache has
// no flame grid, and with the mapping of the cache's temperature units to kelvin.
void adaptFireShader(const PyroBinding& binding, ShaderDesc* shader);

}  // namespace mirage
