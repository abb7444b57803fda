// `[[volume]] precision` and `precision_tolerance`: the precision a volume's scalar grids are
// held in (volume/grid_precision.h; docs/scene-file.md, "Grid precision").
#pragma once

#include <string>
#include <vector>

#include "scene/toml_reader.h"
#include "volume/grid_precision.h"
#include "volume/vdb_file.h"

namespace mirage {

// The volume's precision as it states it (stated: false, float, when it does not). Refuses an
// unknown name (naming the key and the accepted ones), a tolerance for any precision but fpn,
// and either key on a box volume, which has no grids.
PrecisionSpec readVolumePrecision(const TableReader& volume, bool boxed);

// The precision a volume's grids load at, and why, in words for `mirage info`.
struct PrecisionChoice {
    PrecisionSpec spec;
    std::string why;
};

// The stated precision; unstated, half (NanoVDB Fp16) when every grid the volume reads (`read`,
// from the file's metadata) is stored as half floats and too big for a float dense copy
// (volume/dense_block.h), and no expression writes one; else float. Fp16 then errs ~1/35 to
// 1/220 as much as the half storage already did (RMS), so it loses nothing the file kept, and
// halves the memory; a grid small enough for a dense copy keeps float, whose lookups read the
// copy (docs/scene-file.md, "Grid precision", the figures).
PrecisionChoice choosePrecision(const PrecisionSpec& stated, const std::vector<GridInfo>& read,
                                bool expressionWrites);

}  // namespace mirage
