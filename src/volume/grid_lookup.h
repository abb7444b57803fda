// What looking a grid up needs of NanoVDB: the accessors of scalar and vector grids, the inline
// trilinear sample of a scalar grid (the renderer's hottest call), and the NanoVDB grids behind
// FloatGrid and VectorGrid. Include it only where grids are looked up or walked — the medium's
// lookups, the majorant build, the photon emitter, the optical-depth march, the volume stage —
// and not from a header: everywhere else the grids are handles (volume/grid.h,
// volume/vector_grid.h), and NanoVDB's ~7 000 header lines stay out of the build.
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <cmath>

#include "volume/dense_block.h"
#include "volume/grid.h"
#include "volume/leaf_stencil.h"
#include "volume/vector_grid.h"

namespace mirage {

// NanoVDB's read accessors, under the names the handles declare.
class FloatGrid::Accessor : public nanovdb::FloatGrid::AccessorType {
public:
    using Base = nanovdb::FloatGrid::AccessorType;
    explicit Accessor(const nanovdb::FloatGrid& grid) : Base(grid.getAccessor()) {}
};

class VectorGrid::Accessor : public nanovdb::Vec3fGrid::AccessorType {
public:
    using Base = nanovdb::Vec3fGrid::AccessorType;
    explicit Accessor(const nanovdb::Vec3fGrid& grid) : Base(grid.getAccessor()) {}
};

inline const auto* FloatGrid::grid() const { return mHandle->grid<float>(); }

inline FloatGrid::Accessor FloatGrid::accessor() const { return Accessor(*grid()); }

inline auto FloatGrid::indexBounds() const { return grid()->indexBBox(); }

inline float FloatGrid::sample(const Accessor& acc, const Vec3& pObject) const {
    using Leaf = nanovdb::NanoLeaf<float>;
    const Vec3 pi = mIndexMap.toIndex(pObject);
    const float fi[3] = {std::floor(pi.x), std::floor(pi.y), std::floor(pi.z)};
    const nanovdb::Coord ijk{int32_t(fi[0]), int32_t(fi[1]), int32_t(fi[2])};
    const float u[3] = {pi.x - fi[0], pi.y - fi[1], pi.z - fi[2]};
    uint32_t o;
    if (mDense && mDense->holdsStencil(ijk, &o)) {
        const DenseBlock& d = *mDense;
        auto v = [&](int i, int j, int k) { return d.value(o + d.step(i, j, k)); };
        return trilinearStencil<float>(v, u);
    }
    constexpr int kStencil[3] = {1, 1, 1};
    if (const Leaf* leaf = leafHoldingBox<Leaf>(acc, ijk, kStencil))
        return trilinearInLeaf(*leaf, Leaf::CoordToOffset(ijk), u);
    return nanovdb::createSampler<1, Accessor::Base, false>(acc)(nanovdb::Vec3f(pi.x, pi.y, pi.z));
}

inline const auto* VectorGrid::grid() const { return mHandle->grid<nanovdb::Vec3f>(); }

inline VectorGrid::Accessor VectorGrid::accessor() const { return Accessor(*grid()); }

inline auto VectorGrid::indexBounds() const { return grid()->indexBBox(); }

}  // namespace mirage
