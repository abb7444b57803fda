// Grids held as dense arrays in memory (a numpy array from Python, a host application's voxel
// buffer) written as one OpenVDB file, so that they reach a scene through the same loader,
// bindings, expressions and messages as a cache on disk. This header does not include OpenVDB;
// the definition lives in asset_writer.cpp, the tools' one OpenVDB translation unit.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace mirage {

// One grid: dims[0]·dims[1]·dims[2] voxels of `components` floats (1: a float fog volume; 3: a
// vec3s grid, a velocity in world units per second), x slowest and z fastest (the C order of
// values[x][y][z][c]). values[0][0][0] is at index `offset`; a voxel's world position is
// origin + voxelSize · index, as in OpenVDB's linear transform.
struct DenseGrid {
    std::string name;
    std::array<int64_t, 3> dims{0, 0, 0};
    int components = 1;
    const float* values = nullptr;
    double voxelSize = 1.0;
    std::array<int32_t, 3> offset{0, 0, 0};
    Vec3d origin{0.0, 0.0, 0.0};
};

// Writes `grids` to `path` (atomically, blosc-compressed). Voxels equal to zero stay inactive,
// as in every fog volume, so an array's empty space costs nothing in the file or the renderer.
// Throws MirageError naming the grid for an empty or oversized array, a non-finite value, or a
// voxel size that is not a positive finite number, and naming `path` when it cannot be written.
void writeDenseVdbFile(const std::string& path, const std::vector<DenseGrid>& grids);

}  // namespace mirage
