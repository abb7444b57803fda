// Test scaffolding for the volume readers: small OpenVDB files given grid by grid and voxel by
// voxel (bad values, wrong types and classes, tiles, unnamed grids, several grids per file),
// and OpenVDB's own lookup to compare NanoVDB against. This header does not include OpenVDB;
// test_grids.cpp, the tests' only translation unit that does, does.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace mirage {

// A small grid given voxel by voxel.
struct TestGridSpec {
    struct Voxel {
        Voxel() = default;
        Voxel(int32_t i_, int32_t j_, int32_t k_, double value_, Vec3d vector_ = Vec3d())
            : i(i_), j(j_), k(k_), value(value_), vector(vector_) {}
        int32_t i = 0, j = 0, k = 0;
        double value = 0.0;  // scalar value (bool: value != 0)
        Vec3d vector;        // vec3s grids use this instead of value
    };
    // A constant active tile holding the 8³ (level 1), 128³ (level 2) or 4096³ (level 3)
    // voxels around index (i, j, k).
    struct Tile {
        Tile() = default;
        Tile(int32_t i_, int32_t j_, int32_t k_, int level_, double value_)
            : i(i_), j(j_), k(k_), level(level_), value(value_) {}
        int32_t i = 0, j = 0, k = 0;
        int level = 1;
        double value = 0.0;
    };

    std::string name = "density";          // "" writes an unnamed grid
    // "float", "double", "vec3s", "bool", "int32", "int64", "vec3d", "vec3i", "mask"
    std::string valueType = "float";
    std::string gridClass = "fog volume";  // "fog volume", "level set", "staggered", "unknown"
    double voxelSize = 0.1;                // metres
    Vec3d origin;                          // object-space position of index (0,0,0), metres
    double background = 0.0;
    bool saveAsHalf = false;    // store float values as 16-bit half
    // The index → object map: "uniform" (a UniformScaleTranslateMap), "scale" (voxels ×2 along
    // y), "affine" (rotated 30° about z) or "frustum" (a NonlinearFrustumMap).
    std::string map = "uniform";
    // Share the previous grid's tree (same type): OpenVDB writes this grid as an instance.
    bool shareTreeWithPrevious = false;
    std::vector<Voxel> voxels;  // active voxels
    // Inactive voxels that store a value (a leaf keeps one for each of its 512 voxels): what
    // grid expressions must leave alone.
    std::vector<Voxel> inactiveVoxels;
    std::vector<Tile> tiles;
};

// Writes the grids, in this order, to one OpenVDB file. `compression` is "blosc" (falls back
// to zip when this OpenVDB lacks Blosc), "zip" or "none"; note that OpenVDB never zips fog
// volumes and level sets, so a zip test needs gridClass "unknown".
void writeTestGrids(const std::string& path, const std::vector<TestGridSpec>& specs,
                    const std::string& compression = "blosc");
inline void writeTestGrid(const std::string& path, const TestGridSpec& spec,
                          const std::string& compression = "blosc") {
    writeTestGrids(path, {spec}, compression);
}


// OpenVDB's own trilinear lookup (tools::BoxSampler) of the float grid `gridName` of an OpenVDB
// file at each point, in index space (indexSpace = true) or object space.
std::vector<double> openvdbSampleForTest(const std::string& path, const std::string& gridName,
                                         const std::vector<Vec3d>& points, bool indexSpace);

// The bytes of the NanoVDB grid that OpenVDB's whole-grid reader (no delayed loading) and
// NanoVDB's converter make of the float or vec3s grid `gridName` — the load before the leaves
// were read in parallel — with the loader's statistics and checksum settings.
std::string eagerNanoVdbForTest(const std::string& path, const std::string& gridName);

}  // namespace mirage
