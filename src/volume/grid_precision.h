// The precision a scalar grid's voxels are held in: a user's trade of memory against error
// (`[[volume]] precision`, docs/scene-file.md).
//
// "float" keeps NanoVDB's 32-bit floats. The others are NanoVDB's quantised leaves (Museth,
// "NanoVDB: A GPU-friendly and portable VDB data structure", HPG 2021): each 8³ leaf stores its
// minimum m and a step q = (M − m)/(2^b − 1) over its own value range [m, M], and per voxel the
// b-bit code round((v − m)/q), decoded as m + code·q. "half" is Fp16 (b = 16: NanoVDB's 16-bit
// fixed point, the size of an IEEE half, not its format), "fp8" and "fp4" are Fp8 and Fp4, and
// "fpn" is FpN, which picks per leaf the fewest bits of 1, 2, 4, 8 or 16 whose decoded values
// all lie within an absolute tolerance of the floats (16 when even that misses it).
//
// A decoded voxel is off by at most half a step, q/2 = (M − m)/(2(2^b − 1)) ≤ vmax/(2(2^b − 1))
// for a fog volume (values in [0, vmax]): vmax/131070 for half, vmax/510 for fp8, vmax/30 for
// fp4; for fpn, the tolerance. A trilinear lookup is a convex combination of decoded voxels, so
// it is off by at most as much (quantisationBound below).
//
// Internal nodes, tiles and the root stay float in every precision: only leaves shrink.
#pragma once

#include <cstdint>
#include <string>

namespace mirage {

enum class GridPrecision { Float, Half, Fp8, Fp4, FpN };

// What a volume asks of its grids: the codec, and FpN's tolerance as a fraction of the grid's
// largest stored value (so one number suits densities of 1 and temperatures of 2000 K alike).
struct PrecisionSpec {
    GridPrecision precision = GridPrecision::Float;
    float relativeTolerance = kDefaultFpnTolerance;
    // Whether the scene said it (`precision` or `precision_tolerance`); unstated, the loader
    // chooses (scene/precision_loader.h, choosePrecision).
    bool stated = false;
    static constexpr float kDefaultFpnTolerance = 1e-3f;
    bool operator==(const PrecisionSpec& o) const {
        return precision == o.precision &&
               (precision != GridPrecision::FpN || relativeTolerance == o.relativeTolerance);
    }
};

constexpr GridPrecision kAllPrecisions[] = {GridPrecision::Float, GridPrecision::Half,
                                            GridPrecision::Fp8, GridPrecision::Fp4,
                                            GridPrecision::FpN};

// "float", "half", "fp8", "fp4", "fpn": the names the scene file uses.
const char* precisionName(GridPrecision p);
// The precision called `name`; false when there is none.
bool parsePrecision(const std::string& name, GridPrecision* p);
// "float, half, fp8, fp4 or fpn": for the message that refuses another name.
std::string precisionNames();

// The bits a fixed-width codec stores per voxel (32 for float); 16 for fpn, its widest.
int precisionBits(GridPrecision p);

// The largest error of a decoded voxel (and so of a trilinear lookup) of a grid whose stored
// values lie in [0, maxValue], before float rounding: half a quantisation step, or fpn's
// absolute tolerance. 0 for float.
float quantisationBound(const PrecisionSpec& spec, float maxValue);

// The bytes of one 8³ leaf node in NanoVDB at precision p (fpn: at its widest, 16 bits).
uint64_t leafNodeBytes(GridPrecision p);

// A tree's bytes at `to` from its bytes at `from` and its leaf count (only leaves differ): exact;
// but fpn's leaves vary: to fpn, the bound of 16-bit leaves; from fpn to another, 0 (unknown).
uint64_t treeBytesAt(GridPrecision to, GridPrecision from, uint64_t bytes, uint64_t leaves);

}  // namespace mirage
