#include "scene/pyro_binding.h"

#include <algorithm>
#include <cstdio>

namespace mirage {

namespace {

std::string firstOf(const std::vector<std::string>& grids,
                    std::initializer_list<const char*> names) {
    for (const char* n : names)
        if (std::find(grids.begin(), grids.end(), n) != grids.end()) return n;
    return "";
}

std::string number(float v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", double(v));
    return b;
}

}  // namespace

PyroBinding bindPyroCache(const std::vector<std::string>& grids, const GridMaximum& maxValue) {
    PyroBinding b;
    const std::string flame = firstOf(grids, {"flame", "flames"});
    const std::string temperature = firstOf(grids, {"temperature", "heat", "temp"});
    b.flame = !flame.empty();
    float tMax = 0.f;
    if (!temperature.empty()) tMax = maxValue(temperature);
    const bool kelvin = tMax > kKelvinThreshold;
    // A fire: a flame grid, a temperature hot enough to glow, or Houdini's combustion `heat`.
    // A relative `temperature` alone is a smoke simulation's buoyancy, not light.
    const bool glows = kelvin && tMax >= kGlowKelvin;
    const bool fire = b.flame || glows || temperature == "heat";
    if (!fire) {
        if (!temperature.empty())
            b.notes.push_back(
                "grid '" + temperature + "' (max " + number(tMax) + ") is " +
                (kelvin ? "below " + number(kGlowKelvin) + " K, too cool to glow visibly,"
                        : "a relative temperature") +
                " and there is no flame grid: a smoke's warm air, not bound (the smoke "
                "shader); bind it with the fire shader in a scene file to make it glow");
        return b;
    }
    b.shader = "fire";
    b.notes.push_back("a pyro cache (" +
                      std::string(b.flame ? "flame grid '" + flame + "'"
                                          : "temperature grid '" + temperature + "'") +
                      "): the built-in fire shader, blackbody emission");
    if (b.flame) b.bind.emplace_back("flame", flame);
    if (temperature.empty()) {
        b.bind.emplace_back("temperature", flame);
        b.temperatureScale = kFlameKelvinRange;
        b.temperatureOffset = kAmbientKelvin;
        b.notes.push_back(
            "no temperature grid: temperature ← flame, T = " + number(kAmbientKelvin) + " K + " +
            number(kFlameKelvinRange) + " K × flame");
        return b;
    }
    b.bind.emplace_back("temperature", temperature);
    if (kelvin) {
        b.notes.push_back("temperature ← '" + temperature + "' in kelvin (max " + number(tMax) +
                          " K)");
    } else {
        b.temperatureScale = kKelvinPerRelativeUnit;
        b.temperatureOffset = kAmbientKelvin;
        b.notes.push_back("temperature ← '" + temperature + "', relative (max " + number(tMax) +
                          " ≤ " + number(kKelvinThreshold) + "): T = " + number(kAmbientKelvin) +
                          " K + " + number(kKelvinPerRelativeUnit) + " K × value");
    }
    return b;
}

void adaptFireShader(const PyroBinding& binding, ShaderDesc* shader) {
    if (!binding.flame) {
        auto& c = shader->components;
        c.erase(std::remove_if(c.begin(), c.end(),
                               [](const MediumComponent& m) { return m.grid == "flame"; }),
                c.end());
    }
    if (shader->emission) {
        shader->emission->temperatureScale = binding.temperatureScale;
        shader->emission->temperatureOffset = binding.temperatureOffset;
    }
}

}  // namespace mirage
