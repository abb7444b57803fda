// Object space (metres) to a NanoVDB grid's index space, with the bits of the grid's own
// worldToIndexF, but without its calls to fmaf where the map has no rotation.
//
// NanoVDB's map applies its 3×3 inverse matrix with fmaf (NanoVDB.h, matMult). The project is
// built for the x86-64 baseline, which has no FMA instruction, so each fmaf is a call into libm:
// six per lookup, 3–4 % of a single-scattering render (perf, race scene). Grids written by
// OpenVDB with a uniform or per-axis voxel size have a diagonal matrix, and there the sums reduce
// exactly: fmaf(x, m0, fmaf(y, 0, z·0)) = round(x·m0) + (±0) = round(x·m0), up to the sign of a
// zero, which neither floor() nor the stencil's fractions can tell apart. Rotated or sheared
// maps keep NanoVDB's own transform.
#pragma once

#include <nanovdb/NanoVDB.h>

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
    explicit IndexMap(const nanovdb::Map& map) : mMap(&map) {
        const float* m = map.mInvMatF;
        mDiagonal = isDiagonal3x3(m);
        for (int a = 0; a < 3; ++a) {
            mScale[a] = m[4 * a];
            mOffset[a] = map.mVecF[a];
        }
    }

    nanovdb::Vec3f toIndex(const nanovdb::Vec3f& p) const {
        if (!mDiagonal) return mMap->applyInverseMapF(p);
        return {(p[0] - mOffset[0]) * mScale[0], (p[1] - mOffset[1]) * mScale[1],
                (p[2] - mOffset[2]) * mScale[2]};
    }

private:
    const nanovdb::Map* mMap = nullptr;
    bool mDiagonal = false;
    float mScale[3] = {0.f, 0.f, 0.f};
    float mOffset[3] = {0.f, 0.f, 0.f};
};

}  // namespace mirage
