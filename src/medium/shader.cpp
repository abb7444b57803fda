#include "medium/shader.h"

#include <algorithm>

namespace mirage {

std::vector<std::string> ShaderDesc::gridSlots() const {
    std::vector<std::string> slots;
    auto add = [&](const std::string& s) {
        if (!s.empty() && std::find(slots.begin(), slots.end(), s) == slots.end())
            slots.push_back(s);
    };
    for (const auto& c : components) add(c.grid);
    if (emission) add(emission->temperatureGrid);
    return slots;
}

bool ShaderDesc::spectralCoefficients() const {
    for (const auto& c : components)
        if (!c.sigmaA.isConstant() || !c.sigmaS.isConstant() || !c.sigmaAExponent.isConstant())
            return true;
    return false;
}

bool ShaderDesc::fluorescent() const {
    for (const auto& c : components)
        if (c.fluorescent()) return true;
    return false;
}

}  // namespace mirage
