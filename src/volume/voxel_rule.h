// The voxel rule (docs/hostile-input.md, "Input rules") on a NanoVDB grid read from a file,
// and its one warning per grid. No OpenVDB here: it runs on the converted grids.
#pragma once

#include <cstdint>
#include <string>

#include <nanovdb/NanoVDB.h>

namespace mirage {

// The largest voxel value a grid keeps (grid units: density, K, mg/m³). Far above any physical
// density or temperature, and low enough that scale × value × cross-section stays finite in
// float for any sane shader (Medium refuses the products that do not).
constexpr float kMaxVoxelValue = 1e10f;

// Voxels the rule changed: set to 0, and clamped (or, for vectors, shortened).
struct SanitizeCounts {
    uint64_t zeroed = 0, clamped = 0;
    uint64_t total() const { return zeroed + clamped; }
};

// NaN and negative values (−∞ included) become 0, +∞ and values above kMaxVoxelValue become
// kMaxVoxelValue, in leaves and tiles; the node statistics and checksum are brought up to date.
SanitizeCounts sanitizeScalarVoxels(nanovdb::FloatGrid& grid);

// One warning per (file, grid) on stderr, naming both and the counts.
void warnSanitizedOnce(const std::string& path, const std::string& label,
                       const SanitizeCounts& count, bool vectors = false);

}  // namespace mirage
