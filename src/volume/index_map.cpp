#include "volume/index_map.h"

#include <nanovdb/NanoVDB.h>

namespace mirage {

IndexMap::IndexMap(const nanovdb::Map& map) : mMap(&map) {
    const float* m = map.mInvMatF;
    mDiagonal = isDiagonal3x3(m);
    for (int a = 0; a < 3; ++a) {
        mScale[a] = m[4 * a];
        mOffset[a] = map.mVecF[a];
    }
}

Vec3 IndexMap::applyInverseMap(const Vec3& p) const {
    const nanovdb::Vec3f q = mMap->applyInverseMapF(nanovdb::Vec3f(p.x, p.y, p.z));
    return {q[0], q[1], q[2]};
}

}  // namespace mirage
