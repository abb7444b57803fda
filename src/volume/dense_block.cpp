#include "volume/dense_block.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace mirage {

std::shared_ptr<const DenseBlock> DenseBlock::of(const nanovdb::FloatGrid& grid,
                                                 uint64_t treeBytes) {
    const nanovdb::CoordBBox active = grid.indexBBox();
    if (active.empty()) return nullptr;
    // The voxels a lookup inside the object bounds (the active box dilated by one voxel) can
    // read: its stencil from floor(index) reaches one voxel further up.
    const nanovdb::Coord lo = active.min() - nanovdb::Coord(1);
    const nanovdb::Coord hi = active.max() + nanovdb::Coord(2);
    uint64_t dim[3], count = 1;
    for (int a = 0; a < 3; ++a) {
        dim[a] = uint64_t(int64_t(hi[a]) - lo[a] + 1);
        count *= dim[a];
        if (count > kDenseMaxBytes / sizeof(float)) return nullptr;
    }
    if (!denseCopyFits(count * sizeof(float), treeBytes)) return nullptr;

    auto block = std::make_shared<DenseBlock>();
    block->mMin = lo;
    for (int a = 0; a < 3; ++a) block->mDim[a] = uint32_t(dim[a]);
    block->mValues.reset(new float[count]);
    block->mCount = count;
    float* values = block->mValues.get();
    // By blocks of 8³ aligned with the leaves: a leaf's values copied from its array, else the
    // one value the tree holds over the whole block (a tile's or the background) — what a
    // lookup of each voxel returns, for one probe per block. In parallel over x slabs of blocks.
    const int32_t firstBlock = lo[0] & ~7;
    const int32_t slabs = (hi[0] - firstBlock) / 8 + 1;
    const auto& root = grid.tree().root();
    tbb::parallel_for(
        tbb::blocked_range<int32_t>(0, slabs), [&](const tbb::blocked_range<int32_t>& r) {
            for (int32_t s = r.begin(); s != r.end(); ++s) {
                const int32_t bx = firstBlock + 8 * s;
                for (int32_t by = lo[1] & ~7; by <= hi[1]; by += 8)
                    for (int32_t bz = lo[2] & ~7; bz <= hi[2]; bz += 8) {
                        const nanovdb::Coord origin(bx, by, bz);
                        const auto* leaf = root.probeLeaf(origin);
                        const float fill = leaf ? 0.f : root.getValue(origin);
                        for (int32_t x = std::max(bx, lo[0]); x <= std::min(bx + 7, hi[0]); ++x)
                            for (int32_t y = std::max(by, lo[1]); y <= std::min(by + 7, hi[1]);
                                 ++y) {
                                float* row =
                                    values +
                                    (uint64_t(x - lo[0]) * dim[1] + uint64_t(y - lo[1])) * dim[2];
                                for (int32_t z = std::max(bz, lo[2]); z <= std::min(bz + 7, hi[2]);
                                     ++z)
                                    row[z - lo[2]] =
                                        leaf ? leaf->data()->mValues[((x & 7) << 6) |
                                                                     ((y & 7) << 3) | (z & 7)]
                                             : fill;
                            }
                    }
            }
        });
    return block;
}

}  // namespace mirage
