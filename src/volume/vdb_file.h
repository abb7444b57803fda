// Reading OpenVDB files: validation, grid listing, and conversion of the grids a shader uses
// to NanoVDB. This header does not include OpenVDB (its headers cost ~28 s and ~1 GB per
// translation unit); only vdb_file.cpp, asset_writer.cpp and grid_expression.cpp do.
//
// Both OpenVDB (.vdb) and NanoVDB (.nvdb) files are accepted; the format is recognised by the
// magic number, not the extension. Grids are addressed by name, or as "#N" for the N-th grid in
// file order (0-based), which is the only way to address an unnamed grid.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "volume/grid.h"
#include "volume/grid_expression.h"
#include "volume/vector_grid.h"
#include "volume/voxel_rule.h"

namespace mirage {

struct GridInfo {
    std::string name;       // may be empty: unnamed grids are addressed as "#<index>"
    std::string valueType;  // "float", "half" (stored as half), "double", "vec3s", "bool", ...
    std::string gridClass;  // "fog volume", "level set", "staggered", "unknown"
    Vec3d voxelSize;        // metres (object space)
    int64_t indexMin[3] = {0, 0, 0}, indexMax[3] = {0, 0, 0};  // active index bbox, inclusive
    Bounds3 objectBounds;  // active voxels' extent in object (VDB world) space, metres
    uint64_t activeVoxels = 0;
    uint64_t memoryBytes = 0;  // in-core size OpenVDB reports (file metadata when present)
    std::string transform;     // human-readable index → object map
    std::string compression;   // "blosc", "zip", "none", ...
};

struct VdbFileInfo {
    std::string path;
    std::string format;  // "OpenVDB" or "NanoVDB"
    std::string fileVersion;
    std::string libraryVersion;   // of the library that wrote the file
    std::vector<GridInfo> grids;  // in file order: grids[N] is "#N"
};

// Checks that `path` exists, is a readable OpenVDB file (magic number, version) and that its
// grid descriptors and offsets lie within the file size, before OpenVDB itself reads it.
// NanoVDB files get the same treatment (segment headers, grid sizes). Throws MirageError
// naming the file and what is wrong.
void validateVdbFile(const std::string& path);

// Lists the grids (metadata only, cheap). Throws MirageError on a bad file.
VdbFileInfo inspectVdbFile(const std::string& path);

// Reads one scalar grid — by name, or "#N" for the N-th grid (0-based) — from an OpenVDB file
// (float, half or double storage; Blosc/zip) or a NanoVDB file (.nvdb) and returns it as a
// NanoVDB float grid. Voxels that are NaN or negative are set to 0, voxels that are +inf or
// above kMaxVoxelValue are clamped to it, and both are reported by one warning per grid naming
// the file, grid and counts (the documented rule, see docs/hostile-input.md, "Input rules").
// Throws MirageError if the file or grid is missing, or the grid is not a scalar fog volume
// (level set, vector, bool or integer grid, background other than 0, non-affine transform).
//
// `streamed` half, fp8 or fp4: an OpenVDB grid's leaves are encoded at that precision as they
// are read (volume/openvdb_to_nano.h), no float copy made; the grids that converter does not
// take (NanoVDB files, a staggered class, a name too long for NanoVDB's header), and fpn, come
// back as float, for quantiseGrid to finish (loadGridsAt, volume/grid_quantise.h, does both).
FloatGrid loadFloatGrid(const std::string& path, const std::string& gridName,
                        GridPrecision streamed = GridPrecision::Float);

// Reads one 3-vector grid (velocity: vec3s or vec3d, collocated or staggered, vector_grid.h)
// from an OpenVDB file as a NanoVDB Vec3f grid. The vector voxel rule applies: vectors with a
// NaN or infinite component become 0, and vectors longer than kMaxVoxelValue are shortened to
// it, with one warning per grid. Throws MirageError if the file or grid is missing, the grid
// is not a 3-vector grid, its background is not zero, or it comes from a NanoVDB file.
VectorGrid loadVectorGrid(const std::string& path, const std::string& gridName);
// The same from three signed scalar float grids `stem.x`, `stem.y`, `stem.z` (collocated,
// sharing one transform), combined over the union of their active voxels; named `stem`.
VectorGrid loadVectorGridFromScalars(const std::string& path, const std::string& stem);

// Reads the grids `gridNames` of one OpenVDB file, as loadFloatGrid does, after running the
// expressions on them in order (OpenVDB AX, grid_expression.h). The grids an expression names
// are read too, even when they are not in `gridNames` (a mask or a second grid to combine with),
// and dropped afterwards. The voxel rule applies to the results: a NaN or negative value an
// expression produced becomes 0 like one read from the file. `expressionSeconds`, when given,
// receives each expression's compile + run time. Throws MirageError at the expression's
// location when it names a grid the file lacks (listing the file's grids), when the file is a
// NanoVDB file (AX runs on OpenVDB grids), or when AX cannot compile or run it. `streamed` as
// for loadFloatGrid.
std::vector<FloatGrid> loadFloatGrids(const std::string& path,
                                      const std::vector<std::string>& gridNames,
                                      const std::vector<GridExpression>& expressions,
                                      std::vector<double>* expressionSeconds = nullptr,
                                      GridPrecision streamed = GridPrecision::Float);

// A scalar grid's leaf count and the bytes of its NanoVDB tree at float precision, from the
// topology of OpenVDB grid `gridName` alone: no voxel is read (gridReadCount stays). Throws
// MirageError for a missing grid or a tree that is corrupt or cannot be walked.
struct GridTopology {
    uint64_t leaves = 0, floatTreeBytes = 0;
};
GridTopology readGridTopology(const std::string& path, const std::string& gridName);

// How many grids' voxels this process has read from files (metadata reads do not count): what
// tests assert "this grid was never read" with.
uint64_t gridReadCount();

}  // namespace mirage
