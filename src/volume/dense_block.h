// A dense copy of a scalar grid's values over the box its lookups can read, for grids small
// enough that the copy costs little memory.
//
// A trilinear lookup in the sparse tree finds a leaf, and when its 2×2×2 stencil crosses a
// leaf's edge (169 of 512 positions) it reads each of the 8 voxels through the accessor, which
// compares the cached keys of three tree levels each time. Tracking through smoke is little
// else: on the race scene the lookups were a third of a single-scattering frame's instructions
// (callgrind; docs/performance-history.md, "Lookups: a dense copy of small grids"). In a dense
// array the stencil is 8 loads at fixed strides, wherever it falls. The copy holds what the tree
// returns for every voxel of the active box dilated by one voxel and a stencil's reach (inactive
// leaf voxels and tiles included), so a lookup has the same bits either way; outside that box the
// tree answers.
//
// Memory: a cache's dense box is often not much larger than its sparse tree (smoke1: 11.3 MiB
// dense with its margin, 6.7 MiB sparse). The copy is made when it needs at most
// kDenseSmallBytes, or at most kDenseRatio times the tree's buffer, and never more than
// kDenseMaxBytes: a wide, sparse simulation keeps its tree alone.
#pragma once

#include <nanovdb/NanoVDB.h>

#include <cstdint>
#include <memory>

namespace mirage {

constexpr uint64_t kDenseSmallBytes = uint64_t(64) << 20;  // 64 MiB
constexpr uint64_t kDenseRatio = 4;
constexpr uint64_t kDenseMaxBytes = uint64_t(1) << 30;  // 1 GiB

// The budget above: whether a dense copy of denseBytes is made for a tree of treeBytes.
constexpr bool denseCopyFits(uint64_t denseBytes, uint64_t treeBytes) {
    return denseBytes <= kDenseMaxBytes &&
           (denseBytes <= kDenseSmallBytes || denseBytes <= kDenseRatio * treeBytes);
}

class DenseBlock {
public:
    // The copy of `grid` over its active box dilated by one voxel (two above: a stencil's
    // reach), or null when the grid is empty or the copy would break the budget above
    // (treeBytes: the grid's buffer). Filled in parallel by slabs of 8³ blocks aligned with the
    // leaves, each block from its leaf's values or the one value the tree holds over it: what a
    // lookup of each voxel returns, for any thread count.
    static std::shared_ptr<const DenseBlock> of(const nanovdb::FloatGrid& grid, uint64_t treeBytes);

    // Whether the 2×2×2 stencil from voxel ijk lies inside the block; if so *offset is the
    // array offset of ijk.
    bool holdsStencil(const nanovdb::Coord& ijk, uint32_t* offset) const {
        uint32_t o = 0;
        for (int a = 0; a < 3; ++a) {
            const int64_t d = int64_t(ijk[a]) - mMin[a];
            if (d < 0 || d >= int64_t(mDim[a]) - 1) return false;
            o = o * mDim[a] + uint32_t(d);
        }
        *offset = o;
        return true;
    }
    // Offset of the voxel (i, j, k) steps from the voxel at offset o: x-major, z fastest.
    uint32_t step(int i, int j, int k) const {
        return uint32_t(i) * mDim[1] * mDim[2] + uint32_t(j) * mDim[2] + uint32_t(k);
    }
    float value(uint32_t o) const { return mValues[o]; }
    uint64_t bytes() const { return mCount * sizeof(float); }

private:
    nanovdb::Coord mMin;
    uint32_t mDim[3] = {0, 0, 0};
    // Not zeroed when allocated (a vector would zero it on one thread, a second at 10⁸
    // voxels): of() writes every value, in parallel.
    std::unique_ptr<float[]> mValues;
    uint64_t mCount = 0;
};

}  // namespace mirage
