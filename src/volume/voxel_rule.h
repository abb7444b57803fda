// The voxel rule (docs/hostile-input.md, "Input rules") on a NanoVDB grid read from a file,
// and its one warning per grid. No OpenVDB here: it runs on the converted grids, given by their
// handles so that the limit below is known without NanoVDB's headers.
#pragma once

#include <cstdint>
#include <string>

#include "volume/nanovdb_fwd.h"

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

// The rule on one stored value covering `voxels` voxels (a tile covers many): NaN and negative
// values (−∞ included) become 0, +∞ and values above kMaxVoxelValue become kMaxVoxelValue,
// counted in *count.
inline void applyScalarVoxelRule(float& v, uint64_t voxels, SanitizeCounts& count) {
    if (!(v >= 0.f)) {  // NaN or negative
        v = 0.f;
        count.zeroed += voxels;
    } else if (v > kMaxVoxelValue) {  // +∞ included
        v = kMaxVoxelValue;
        count.clamped += voxels;
    }
}

// The rule on every stored value, in leaves and tiles, of the handle's float grid; the node
// statistics and checksum are brought up to date.
SanitizeCounts sanitizeScalarVoxels(nanovdb::GridHandle<nanovdb::HostBuffer>& handle);

// The voxel rule for vectors, applied to every stored value of the handle's Vec3f grid (leaf
// voxels, active or not, and tiles): a vector with a NaN or infinite component becomes 0 (it
// would poison every lookup that reads it), and one longer than `maxMagnitude` is shortened to
// that length, direction kept. Returns the number of voxels changed (a tile counts all of its
// voxels); *zeroed, when given, receives how many of them were zeroed. (vector_grid.cpp)
uint64_t sanitizeVectorVoxels(nanovdb::GridHandle<nanovdb::HostBuffer>& handle, float maxMagnitude,
                              uint64_t* zeroed = nullptr);

// One warning per (file, grid) on stderr, naming both and the counts.
void warnSanitizedOnce(const std::string& path, const std::string& label,
                       const SanitizeCounts& count, bool vectors = false);

}  // namespace mirage
