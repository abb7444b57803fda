// A scalar volume grid in NanoVDB form: the hot-path representation every shader samples.
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <cmath>
#include <memory>
#include <string>

#include "core/math.h"
#include "volume/dense_block.h"
#include "volume/index_map.h"
#include "volume/leaf_stencil.h"

namespace mirage {

class FloatGrid {
public:
    using Accessor = nanovdb::FloatGrid::AccessorType;
    using Sampler = nanovdb::SampleFromVoxels<Accessor, 1, false>;  // trilinear

    FloatGrid() = default;
    FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
              uint64_t sanitizedVoxels = 0);

    bool valid() const { return mGrid != nullptr; }
    const std::string& name() const { return mName; }
    const nanovdb::FloatGrid* grid() const { return mGrid; }
    Accessor accessor() const { return mGrid->getAccessor(); }

    // Trilinear value at an object-space point (metres). Outside the active region the
    // background (0 for fog volumes) is returned.
    //
    // Bit for bit NanoVDB's SampleFromVoxels<1> (the same lerps in the same order), read from
    // the grid's dense copy where it has one (volume/dense_block.h), else, when the 2×2×2
    // stencil lies inside one 8³ leaf — 343 of 512 cell positions — from that leaf at fixed
    // offsets, instead of 8 accessor lookups that each compare the cached keys of three tree
    // levels. It is the renderer's hottest call (every tentative collision and every
    // shadow-ray control reads it).
    float sample(const Accessor& acc, const Vec3& pObject) const {
        using Leaf = nanovdb::NanoLeaf<float>;
        nanovdb::Vec3f pi = mIndexMap.toIndex(nanovdb::Vec3f(pObject.x, pObject.y, pObject.z));
        const float fi[3] = {std::floor(pi[0]), std::floor(pi[1]), std::floor(pi[2])};
        const nanovdb::Coord ijk{int32_t(fi[0]), int32_t(fi[1]), int32_t(fi[2])};
        const float u[3] = {pi[0] - fi[0], pi[1] - fi[1], pi[2] - fi[2]};
        uint32_t o;
        if (mDense && mDense->holdsStencil(ijk, &o)) {
            const DenseBlock& d = *mDense;
            auto v = [&](int i, int j, int k) { return d.value(o + d.step(i, j, k)); };
            return trilinearStencil<float>(v, u);
        }
        constexpr int kStencil[3] = {1, 1, 1};
        if (const Leaf* leaf = leafHoldingBox<Leaf>(acc, ijk, kStencil))
            return trilinearInLeaf(*leaf, Leaf::CoordToOffset(ijk), u);
        return nanovdb::createSampler<1, Accessor, false>(acc)(pi);
    }

    Bounds3 objectBounds() const { return mObjectBounds; }  // active voxels, dilated by 1 voxel
    // Index-space active bbox, inclusive.
    nanovdb::CoordBBox indexBounds() const { return mGrid->indexBBox(); }
    float maxValue() const { return mMaxValue; }
    uint64_t activeVoxels() const { return mGrid->activeVoxelCount(); }
    uint64_t treeBytes() const { return mHandle ? mHandle->size() : 0; }  // the NanoVDB buffer
    uint64_t denseBytes() const { return mDense ? mDense->bytes() : 0; }  // the dense copy
    uint64_t memoryBytes() const { return treeBytes() + denseBytes(); }
    uint64_t sanitizedVoxels() const { return mSanitized; }
    // The same grid without its dense copy: lookups through the tree alone (the copy's tests).
    FloatGrid treeOnly() const {
        FloatGrid g = *this;
        g.mDense.reset();
        return g;
    }

private:
    std::shared_ptr<nanovdb::GridHandle<nanovdb::HostBuffer>> mHandle;
    const nanovdb::FloatGrid* mGrid = nullptr;
    IndexMap mIndexMap;  // object → index space (volume/index_map.h)
    std::shared_ptr<const DenseBlock> mDense;  // null: the tree alone (volume/dense_block.h)
    std::string mName;
    Bounds3 mObjectBounds;
    float mMaxValue = 0.f;
    uint64_t mSanitized = 0;
};

}  // namespace mirage
