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
#include <variant>

#include "volume/dense_block.h"
#include "volume/grid.h"
#include "volume/leaf_stencil.h"
#include "volume/vector_grid.h"

namespace mirage {

// The NanoVDB grid and read accessor of each precision a scalar grid holds
// (volume/grid_precision.h).
template <typename BuildT>
using NanoAccessor = typename nanovdb::NanoGrid<BuildT>::AccessorType;

template <typename F>
decltype(auto) FloatGrid::visit(F&& f) const {
    switch (mPrecision) {
        case GridPrecision::Half:
            return f(*mHandle->grid<nanovdb::Fp16>());
        case GridPrecision::Fp8:
            return f(*mHandle->grid<nanovdb::Fp8>());
        case GridPrecision::Fp4:
            return f(*mHandle->grid<nanovdb::Fp4>());
        case GridPrecision::FpN:
            return f(*mHandle->grid<nanovdb::FpN>());
        case GridPrecision::Float:
            break;
    }
    return f(*mHandle->grid<float>());
}

// A scalar grid's read accessor, at the grid's precision: one of NanoVDB's five, chosen when the
// accessor is made.
class FloatGrid::Accessor {
public:
    explicit Accessor(const FloatGrid& grid)
        : mAcc(grid.visit([](const auto& g) -> Variant { return g.getAccessor(); })) {}
    // The accessor of a grid at precision BuildT (the grid's own: the caller switched on it).
    template <typename BuildT>
    const NanoAccessor<BuildT>& as() const {
        return *std::get_if<NanoAccessor<BuildT>>(&mAcc);
    }

private:
    using Variant =
        std::variant<NanoAccessor<float>, NanoAccessor<nanovdb::Fp16>, NanoAccessor<nanovdb::Fp8>,
                     NanoAccessor<nanovdb::Fp4>, NanoAccessor<nanovdb::FpN>>;
    Variant mAcc;
};

class VectorGrid::Accessor : public nanovdb::Vec3fGrid::AccessorType {
public:
    using Base = nanovdb::Vec3fGrid::AccessorType;
    explicit Accessor(const nanovdb::Vec3fGrid& grid) : Base(grid.getAccessor()) {}
};

inline const auto* FloatGrid::grid() const { return mHandle->grid<float>(); }

inline FloatGrid::Accessor FloatGrid::accessor() const { return Accessor(*this); }

inline auto FloatGrid::indexBounds() const {
    return visit([](const auto& g) { return g.indexBBox(); });
}

// The voxel whose 2×2×2 stencil a trilinear lookup at index-space point pi reads (its floor),
// and pi's fractions past it.
struct StencilCell {
    nanovdb::Coord ijk;
    float u[3];
    explicit StencilCell(const Vec3& pi) {
        const float fi[3] = {std::floor(pi.x), std::floor(pi.y), std::floor(pi.z)};
        ijk = nanovdb::Coord{int32_t(fi[0]), int32_t(fi[1]), int32_t(fi[2])};
        u[0] = pi.x - fi[0];
        u[1] = pi.y - fi[1];
        u[2] = pi.z - fi[2];
    }
};

// The trilinear lookup at index-space point pi through the tree of a grid at precision BuildT:
// from one leaf when the stencil lies inside it, else NanoVDB's own sampler (tiles, leaf edges,
// the background).
template <typename BuildT>
float sampleTree(const NanoAccessor<BuildT>& acc, const StencilCell& c, const Vec3& pi) {
    const nanovdb::Coord& ijk = c.ijk;
    const float* u = c.u;
    using Leaf = nanovdb::NanoLeaf<BuildT>;
    constexpr int kStencil[3] = {1, 1, 1};
    if (const Leaf* leaf = leafHoldingBox<Leaf>(acc, ijk, kStencil))
        return trilinearInLeaf(*leaf, Leaf::CoordToOffset(ijk), u);
    return nanovdb::createSampler<1, NanoAccessor<BuildT>, false>(acc)(
        nanovdb::Vec3f(pi.x, pi.y, pi.z));
}

inline float FloatGrid::sample(const Accessor& acc, const Vec3& pObject) const {
    const Vec3 pi = mIndexMap.toIndex(pObject);
    if (mPrecision != GridPrecision::Float) return sampleQuantised(acc, pi);
    const StencilCell c(pi);
    uint32_t o;
    if (mDense && mDense->holdsStencil(c.ijk, &o)) {
        const DenseBlock& d = *mDense;
        auto v = [&](int i, int j, int k) { return d.value(o + d.step(i, j, k)); };
        return trilinearStencil<float>(v, c.u);
    }
    return sampleTree<float>(acc.as<float>(), c, pi);
}

inline const auto* VectorGrid::grid() const { return mHandle->grid<nanovdb::Vec3f>(); }

inline VectorGrid::Accessor VectorGrid::accessor() const { return Accessor(*grid()); }

inline auto VectorGrid::indexBounds() const { return grid()->indexBBox(); }

}  // namespace mirage
