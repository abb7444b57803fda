// The fields behind `mirage make-asset` (tools/asset_writer.h): each asset kind as a pure
// function of position and seed — noise, plume shapes and flows — without OpenVDB, so that the
// writer can evaluate any block of voxels on any thread and get the same bits.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/math.h"

namespace mirage {

struct AssetField {
    std::vector<std::string> grids;  // names, in output order
    std::vector<std::string> units;
    Vec3 lo, hi;                                    // object-space domain (m)
    std::function<void(const Vec3&, float*)> eval;  // writes one value per grid
    // False only when no point of the box [lo, hi] (m) can have a non-zero value: the writer
    // skips the box's voxels without evaluating them. Empty: every box may.
    std::function<bool(const Vec3& lo, const Vec3& hi)> mayCover;
    // The flow (m/s) where the first grid is non-zero, written as the collocated vec3s grid
    // `vel` (Houdini's convention) for motion blur; empty for a still asset.
    std::function<Vec3(const Vec3&)> velocity;
    // `vel`'s voxel size in voxels of the other grids (1 or 2). At 2, a `vel` voxel is active
    // where the first grid is non-zero at its centre.
    int velocityScale = 1;
    // The grids are stored as 16-bit floats in the file (OpenVDB's saveFloatAsHalf), as
    // production pyro caches are.
    bool half = false;
};

// The field of asset `kind` (proceduralAssetKinds()) for `seed`; throws MirageError for an
// unknown kind, listing the valid ones.
AssetField proceduralField(const std::string& kind, uint64_t seed);

// The kinds proceduralField knows, in the order messages list them.
const std::vector<std::string>& proceduralAssetKinds();

}  // namespace mirage
