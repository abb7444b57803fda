// Running a grid expression on OpenVDB grids, for vdb_file.cpp, which reads the grids. It
// includes OpenVDB: include it from there only.
#pragma once

#include <openvdb/openvdb.h>

#include <string>

#include "volume/grid_expression.h"

namespace mirage {

// Compiles the expression with OpenVDB AX and runs it over the active voxels and tiles of the
// grids it writes; `grids` hold at least every grid it names (bindings applied), each carrying
// its name in the file. Returns the seconds spent compiling and running. Throws MirageError at
// expression.where, naming `file`, with AX's message (bounded) when the code does not compile
// or does not run.
inline double runGridExpression(const GridExpression& expression, openvdb::GridPtrVec& grids,
                                const std::string& file) {
    return runGridExpressionOn(expression, &grids, file);
}

}  // namespace mirage
