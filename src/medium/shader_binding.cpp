#include "medium/shader_binding.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/error.h"

namespace mirage {

namespace {

void checkComponentCount(const ShaderDesc& shader) {
    if (shader.components.empty() || int(shader.components.size()) > kMaxComponents)
        throw MirageError("shader '" + shader.name + "': expected 1 to " +
                          std::to_string(kMaxComponents) + " components, found " +
                          std::to_string(shader.components.size()));
}

std::string quotedList(const std::vector<std::string>& names) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "'" : ", '") + n + "'";
    return list;
}

}  // namespace

ShaderBinding::ShaderBinding(ShaderDesc shader, std::vector<FloatGrid> grids, float densityScale)
    : mShader(std::move(shader)), mGrids(std::move(grids)), mDensityScale(densityScale) {
    checkComponentCount(mShader);
    resolveSlots();
}

// Every grid slot the shader names gets the index of its grid, once: the lookups index grids()
// directly. The slots are the shader's own (gridSlots), so a slot without a grid is a caller
// that bound fewer grids than the shader reads.
void ShaderBinding::resolveSlots() {
    const std::vector<std::string> slots = mShader.gridSlots();
    if (slots.size() != mGrids.size()) {
        std::vector<std::string> missing;
        for (size_t i = mGrids.size(); i < slots.size(); ++i) missing.push_back(slots[i]);
        throw MirageError(
            "shader '" + mShader.name + "' reads grid slot(s) " + quotedList(slots) + ", but " +
            std::to_string(mGrids.size()) + " grid(s) are bound" +
            (missing.empty() ? std::string() : "; no grid for " + quotedList(missing)));
    }
    auto indexOf = [&](const std::string& name) {
        if (name.empty()) return -1;
        return int(std::find(slots.begin(), slots.end(), name) - slots.begin());
    };
    for (const auto& c : mShader.components) {
        mComponentSlot.push_back(indexOf(c.grid));
        mModels.push_back(ComponentModel::make(c));
    }
    if (!mShader.emission) return;
    if (mShader.emission->temperatureGrid.empty())
        throw MirageError("shader '" + mShader.name +
                          "': [emission] names no temperature grid slot");
    mTemperatureSlot = indexOf(mShader.emission->temperatureGrid);
}

}  // namespace mirage
