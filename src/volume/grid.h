// A scalar volume grid in NanoVDB form: the hot-path representation every shader samples.
//
// This header names no NanoVDB type, so that the stages which only hold grids, bind them or
// report on them do not compile NanoVDB's ~7 000 header lines. What a lookup needs — the
// accessor, the inline trilinear sample, the NanoVDB grid itself — is in volume/grid_lookup.h,
// which the files that look grids up include (docs/design.md, "Headers").
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/math.h"
#include "volume/grid_precision.h"
#include "volume/index_map.h"
#include "volume/nanovdb_fwd.h"

namespace mirage {

class DenseBlock;

class FloatGrid {
public:
    // A thread's cached path through the tree (volume/grid_lookup.h).
    class Accessor;

    FloatGrid() = default;
    FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
              uint64_t sanitizedVoxels = 0);
    // The same, where the grid's maker saw every value its leaves store (inactive voxels too,
    // as a lookup decodes them): `leafMaximum`, the largest, spares maxValue() a pass over
    // the leaves (gigabytes, in a big cache); nullopt: that pass.
    FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
              uint64_t sanitizedVoxels, std::optional<float> leafMaximum);

    bool valid() const { return mHandle != nullptr; }
    const std::string& name() const { return mName; }
    // The precision its leaves hold (volume/grid_precision.h), read from the NanoVDB grid.
    GridPrecision precision() const { return mPrecision; }
    // The NanoVDB grid of a float grid (a const nanovdb::FloatGrid*; null at another precision).
    inline const auto* grid() const;
    // f(grid) with the NanoVDB grid at its own precision (a const nanovdb::NanoGrid<BuildT>&,
    // BuildT float, Fp16, Fp8, Fp4 or FpN): for the walks that read every precision.
    template <typename F>
    decltype(auto) visit(F&& f) const;
    // A new accessor (a thread's cached path through the tree, at the grid's precision).
    inline Accessor accessor() const;

    // Trilinear value at an object-space point (metres). Outside the active region the
    // background (0 for fog volumes) is returned.
    //
    // Bit for bit NanoVDB's SampleFromVoxels<1> (the same lerps in the same order, of the
    // decoded values at a quantised precision), read from the grid's dense copy where it has
    // one (volume/dense_block.h; float grids only), else, when the 2×2×2
    // stencil lies inside one 8³ leaf — 343 of 512 cell positions — from that leaf at fixed
    // offsets, instead of 8 accessor lookups that each compare the cached keys of three tree
    // levels. It is the renderer's hottest call (every tentative collision and every
    // shadow-ray control reads it). Defined in volume/grid_lookup.h. The precision is one
    // well-predicted branch per lookup; a quantised grid's lookups leave the inline code.
    inline float sample(const Accessor& acc, const Vec3& pObject) const;

    Bounds3 objectBounds() const { return mObjectBounds; }  // active voxels, dilated by 1 voxel
    // Index-space active bbox, inclusive (a nanovdb::CoordBBox).
    inline auto indexBounds() const;
    // The smallest edge of a voxel in object space (metres).
    float minVoxelSize() const { return mMinVoxelSize; }
    float maxValue() const { return mMaxValue; }
    uint64_t activeVoxels() const { return mActiveVoxels; }
    uint64_t treeBytes() const;   // the NanoVDB buffer
    uint64_t denseBytes() const;  // the dense copy
    uint64_t memoryBytes() const { return treeBytes() + denseBytes(); }
    uint64_t leafCount() const { return mLeaves; }
    // The tree's buffer at precision p: exact from the leaf count (fpn: at its widest).
    uint64_t treeBytesAt(GridPrecision p) const {
        return mirage::treeBytesAt(p, mPrecision, treeBytes(), mLeaves);
    }
    uint64_t sanitizedVoxels() const { return mSanitized; }
    // What copies of one grid share, and grids read apart do not: the tree's buffer.
    const void* treeId() const { return mHandle.get(); }
    // The same grid without its dense copy: lookups through the tree alone (the copy's tests).
    FloatGrid treeOnly() const {
        FloatGrid g = *this;
        g.mDense.reset();
        return g;
    }

private:
    // sample() at a quantised precision, from an index-space point (volume/grid.cpp).
    float sampleQuantised(const Accessor& acc, const Vec3& pIndex) const;

    std::shared_ptr<nanovdb::GridHandle<nanovdb::HostBuffer>> mHandle;
    IndexMap mIndexMap;                        // object → index space (volume/index_map.h)
    std::shared_ptr<const DenseBlock> mDense;  // null: the tree alone (volume/dense_block.h)
    std::string mName;
    GridPrecision mPrecision = GridPrecision::Float;
    Bounds3 mObjectBounds;
    float mMinVoxelSize = 0.f;
    float mMaxValue = 0.f;
    uint64_t mActiveVoxels = 0;
    uint64_t mLeaves = 0;
    uint64_t mSanitized = 0;
};

}  // namespace mirage
