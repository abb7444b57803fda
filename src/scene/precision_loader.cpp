#include "scene/precision_loader.h"

namespace mirage {

PrecisionSpec readVolumePrecision(const TableReader& v, bool boxed) {
    PrecisionSpec spec;
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
