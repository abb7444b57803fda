// `[[volume]] precision` and `precision_tolerance`: the precision a volume's scalar grids are
// held in (volume/grid_precision.h; docs/scene-file.md, "Grid precision").
#pragma once

#include "scene/toml_reader.h"
#include "volume/grid_precision.h"

namespace mirage {

// The volume's precision: "float" unless it says otherwise. Refuses an unknown name (naming the
// key and the accepted ones), a tolerance for any precision but fpn, and either key on a box
// volume, which has no grids.
PrecisionSpec readVolumePrecision(const TableReader& volume, bool boxed);

}  // namespace mirage
