// The guide of single scattering's points (transport/scatter_guide.h), filled for a frame
// without a shadow ray.
//
// g at a cell is Σ_lights Li · exp(−τ̃), with τ̃ the optical depth towards the light through a
// coarse copy of the media: each cell's mean σt (from 2×2×2 lookups), stepped through at half a
// cell. It is a deterministic function of the scene, the same for any thread count, and costs
// a fixed share of the frame's own work: the grid is sized to the frame's samples (about eight
// samples per cell, 4³ to 32³ cells), so a small frame gets a small guide. A frame of unknown
// size (0 samples) gets none, and its points are drawn ∝ T σs as without a guide.
//
// Surfaces, the phase function and fluorescence are left out of the guess: they change the
// light a point receives, not whether its estimate is unbiased (any g > 0 keeps it so).
#pragma once

#include <cstdint>
#include <memory>

#include "render/render_scene.h"
#include "transport/scatter_guide.h"

namespace mirage {

// Cells per axis of the guide of a frame of `frameSamples` camera samples (0: no guide).
int scatterGuideResolution(uint64_t frameSamples);

// Null when there is nothing to guide: no light, no medium, or unbounded media (a fog filling
// the scene: no grid to lay over it), or a frame of unknown size.
std::unique_ptr<ScatterGuide> buildScatterGuide(const RenderScene& scene, uint64_t frameSamples);

}  // namespace mirage
