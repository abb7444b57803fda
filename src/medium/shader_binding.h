// A shader bound to a volume's grids: the shader (medium/shader.h), one grid per slot it names
// (in ShaderDesc::gridSlots() order), the law of each component (medium/component.h) and which
// grid each component and the emission's temperature read, resolved once. The medium looks its
// grids up through it (medium/medium.h); the photon emitter (photon/medium_emitter.h) and the
// optical depth along a ray (transport/ray_optical_depth.h) integrate a component's grid
// directly, so they ask it the same questions.
#pragma once

#include <memory>
#include <vector>

#include "medium/component.h"
#include "medium/shader.h"
#include "volume/grid.h"

namespace mirage {

// The most components a shader may sum (a path holds their coefficients in fixed arrays).
constexpr int kMaxComponents = 8;

class ShaderBinding {
public:
    // Refuses (MirageError naming the shader) no component or more than kMaxComponents, and a
    // slot without a grid: `grids` holds one grid per entry of shader.gridSlots().
    ShaderBinding(ShaderDesc shader, std::vector<FloatGrid> grids, float densityScale);

    const ShaderDesc& shader() const { return mShader; }
    const std::vector<FloatGrid>& grids() const { return mGrids; }
    // The law of component i.
    const ComponentModel& componentModel(int i) const { return *mModels[size_t(i)]; }
    // Index into grids() of the grid component i reads, −1 for a constant component; and of the
    // emission's temperature grid, −1 without emission.
    int componentSlot(int i) const { return mComponentSlot[size_t(i)]; }
    int temperatureSlot() const { return mTemperatureSlot; }
    // The grid component i reads, null for a constant component.
    const FloatGrid* componentGrid(int i) const {
        const int slot = componentSlot(i);
        return slot < 0 ? nullptr : &mGrids[size_t(slot)];
    }
    // The scale applied to every component's concentration (the volume's density_scale).
    float densityScale() const { return mDensityScale; }

private:
    void resolveSlots();

    ShaderDesc mShader;
    std::vector<FloatGrid> mGrids;
    float mDensityScale;
    std::vector<std::shared_ptr<const ComponentModel>> mModels;
    std::vector<int> mComponentSlot;
    int mTemperatureSlot = -1;
};

}  // namespace mirage
