#include "scene/precision_loader.h"

#include <algorithm>

#include "core/progress.h"
#include "scene/memory_budget.h"
#include "volume/dense_block.h"

namespace mirage {

namespace {

// The bytes of the float dense copy of a grid with this active index box (DenseBlock::of: the
// box dilated by one voxel below and two above).
uint64_t denseBytesOf(const GridInfo& g) {
    double count = 1;
    for (int a = 0; a < 3; ++a) count *= double(g.indexMax[a] - g.indexMin[a] + 4);
    return uint64_t(std::min(count * sizeof(float), 1e18));
}

}  // namespace

PrecisionChoice choosePrecision(const PrecisionSpec& stated, const std::vector<GridInfo>& read,
                                bool expressionWrites) {
    if (stated.stated) return {stated, "as the scene states"};
    PrecisionChoice chosen{stated, "the default for grids stored as float"};
    if (read.empty()) return chosen;
    for (const GridInfo& g : read)
        if (g.valueType != "half") return chosen;
    if (expressionWrites) {
        chosen.why = "the default where an expression writes a grid (its values are new floats)";
        return chosen;
    }
    for (const GridInfo& g : read) {
        const uint64_t tree = gridBytesBeforeLoad(g, GridPrecision::Float);
        if (g.activeVoxels > 0 && denseCopyFits(denseBytesOf(g), tree)) {
            chosen.why = "the default for grids small enough for a dense copy ('" + g.name +
                         "': " + formatBytes(denseBytesOf(g)) + "), whose lookups are faster";
            return chosen;
        }
    }
    chosen.spec.precision = GridPrecision::Half;
    chosen.why =
        "the default for grids stored as half floats and too big for a dense copy: NanoVDB "
        "Fp16 errs far less than the half storage did, in half the memory of float";
    return chosen;
}

PrecisionSpec readVolumePrecision(const TableReader& v, bool boxed) {
    PrecisionSpec spec;
    spec.stated = v.has("precision") || v.has("precision_tolerance");
    for (const char* key : {"precision", "precision_tolerance"})
        if (boxed && v.has(key))
            v.fail(key, "a box volume is homogeneous: it has no grids to hold at a precision");
    const std::string name = v.getString("precision", precisionName(spec.precision));
    if (!parsePrecision(name, &spec.precision))
        v.fail("precision", "unknown precision '" + name + "'; expected " + precisionNames());
    if (v.has("precision_tolerance")) {
        if (spec.precision != GridPrecision::FpN)
            v.fail("precision_tolerance",
                   "only precision = \"fpn\" takes a tolerance; \"" + name +
                       "\" has a fixed step (docs/scene-file.md, \"Grid precision\")");
        // A fraction of the grid's largest value: below 1e-6 no leaf fits in 16 bits anyway,
        // above 0.5 every leaf becomes 1 bit.
        spec.relativeTolerance = float(v.getNumber(
            "precision_tolerance", double(PrecisionSpec::kDefaultFpnTolerance), 1e-6, 0.5));
    }
    return spec;
}

}  // namespace mirage
