// A loaded float grid re-encoded at a quantised precision (volume/grid_precision.h), by
// NanoVDB's own encoder: the one translation unit beside vdb_file.cpp, grid_expression.cpp and
// tools/asset_writer.cpp that includes OpenVDB, because NanoVDB 10 quantises only while
// converting from an OpenVDB tree.
//
// It runs after the voxel rule (volume/voxel_rule.h): the encoder takes each leaf's range from
// its floats, so a NaN or an infinity would poison the whole leaf. The float grid goes back to
// OpenVDB (every leaf voxel, active or not, and every tile, as stored), then to NanoVDB at the
// precision; the peak of that round trip (two float copies) is the same as reading the float
// grid from its file, and the float copies are dropped once the quantised grid exists. A grid
// read from an OpenVDB file skips all that at half, fp8 and fp4: its leaves are encoded as they
// are read (loadGridsAt; volume/openvdb_to_nano.h), into the same bytes.
#pragma once

#include <vector>

#include "volume/grid.h"
#include "volume/grid_precision.h"
#include "volume/vdb_file.h"

namespace mirage {

// `grid` at spec.precision (itself when that is float, or when the grid is not float). fpn
// keeps every decoded voxel within spec.relativeTolerance × grid.maxValue() of its float.
FloatGrid quantiseGrid(const FloatGrid& grid, const PrecisionSpec& spec);
// Each of `grids` so, each float copy dropped as soon as its quantised grid exists.
std::vector<FloatGrid> quantiseGrids(std::vector<FloatGrid> grids, const PrecisionSpec& spec);

// loadFloatGrids (vdb_file.h) at spec.precision: encoded as the leaves are read where the
// loader can, re-encoded here where it cannot (fpn, a NanoVDB file, a staggered grid).
std::vector<FloatGrid> loadGridsAt(const std::string& path,
                                   const std::vector<std::string>& gridNames,
                                   const std::vector<GridExpression>& expressions,
                                   std::vector<double>* expressionSeconds,
                                   const PrecisionSpec& spec);

}  // namespace mirage
