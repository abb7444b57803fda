// Object space (metres) to a NanoVDB grid's index space, with the bits of the grid's own
// worldToIndexF, but without its calls to fmaf where the map has no rotation.
//
// NanoVDB's map applies its 3×3 inverse matrix with fmaf (NanoVDB.h, matMult). The project is
// built for the x86-64 baseline, which has no FMA instruction, so each fmaf is a call into libm:
// six per lookup, 3–4 % of a single-scattering render (perf, race scene). Grids written by
// OpenVDB with a uniform or per-axis voxel size have a diagonal matrix, and there the sums reduce
// exactly: fmaf(x, m0, fmaf(y, 0, z·0)) = round(x·m0) + (±0) = round(x·m0), up to the sign of a
// zero, which neither floor() nor the stencil's fractions can tell apart. Rotated or sheared
// maps keep NanoVDB's own transform (index_map.cpp).
//
// The header names no NanoVDB type but the map it is built from: grids hold one by value, and
// every stage that sees a grid sees this header (docs/design.md, "Headers").
#pragma once

#include "core/math.h"
#include "volume/nanovdb_fwd.h"

namespace mirage {

// Whether a row-major 3×3 matrix is diagonal: each axis then maps on its own.
template <typename T>
bool isDiagonal3x3(const T* m) {
    return m[1] == T(0) && m[2] == T(0) && m[3] == T(0) && m[5] == T(0) && m[6] == T(0) &&
           m[7] == T(0);
}

class IndexMap {
public:
    IndexMap() = default;
    explicit IndexMap(const nanovdb::Map& map);

    Vec3 toIndex(const Vec3& p) const {
        if (!mDiagonal) return applyInverseMap(p);
        return {(p.x - mOffset[0]) * mScale[0], (p.y - mOffset[1]) * mScale[1],
                (p.z - mOffset[2]) * mScale[2]};
    }

private:
    // NanoVDB's applyInverseMapF, for maps with a rotation or shear.
    Vec3 applyInverseMap(const Vec3& p) const;

    const nanovdb::Map* mMap = nullptr;
    bool mDiagonal = false;
    float mScale[3] = {0.f, 0.f, 0.f};
    float mOffset[3] = {0.f, 0.f, 0.f};
};

}  // namespace mirage
