// Grid expressions: an OpenVDB AX snippet (remap, threshold, combine) that a scene's [[volume]]
// or a shader gives as `expression`, run on the OpenVDB grids of one file after they are read
// and before they become NanoVDB (vdb_file.h, loadFloatGrids). Mirage writes no expression
// parser of its own: AX parses, compiles (LLVM JIT) and runs the code, in Mirage's AX module
// (volume/ax_module.h), loaded the first time a scene has an expression.
//
// AX writes only where the target grid is already active: an expression changes values, never
// topology. This header does not include OpenVDB, nor does grid_expression.cpp: only vdb_file.cpp
// (volume/openvdb_expression.h) and the module.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace mirage {

struct GridExpression {
    std::string code;   // AX source, e.g. "@density = clamp((@density - 0.05) * 4, 0, 1);"
    FileLoc where;      // the `expression` value in the scene or shader file
    std::string label;  // "'expression' in [volume]": how messages name the key
    // AX name → grid name in the file, for names that differ (a shader's expression speaks of
    // its slots, which the volume's `bind` maps to grids). Other names are grids of the file.
    std::vector<std::pair<std::string, std::string>> bindings;
};

// The grids an expression reads and writes, as names in the file (bindings applied), each
// listed once in order of first appearance; a grid both read and written is in both lists.
struct ExpressionAccess {
    std::vector<std::string> reads, writes;
};

// Parses the expression (no compilation) and lists its grids. Throws MirageError at `where`
// with AX's message (bounded) on a syntax error, and for a grid accessed as anything but a
// float (`v@vel`, `i@id`): Mirage's grids are scalar fog volumes.
ExpressionAccess expressionAccess(const GridExpression& expression);

// "reads 'density', 'flame'; writes 'density'": for `mirage info` and messages.
std::string describeAccess(const ExpressionAccess& access);

// runGridExpression (volume/openvdb_expression.h) with its grids, an openvdb::GridPtrVec,
// behind a void*, so that grid_expression.cpp needs no OpenVDB header.
double runGridExpressionOn(const GridExpression& expression, void* grids,
                           const std::string& file);

}  // namespace mirage
