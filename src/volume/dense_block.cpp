#include "volume/dense_block.h"

#include <tbb/parallel_for.h>

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
    block->mValues.resize(count);
    float* values = block->mValues.data();
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, dim[0]), [&](const tbb::blocked_range<uint64_t>& r) {
            auto acc = grid.getAccessor();
            for (uint64_t x = r.begin(); x != r.end(); ++x)
                for (uint64_t y = 0; y < dim[1]; ++y) {
                    float* row = values + (x * dim[1] + y) * dim[2];
                    for (uint64_t z = 0; z < dim[2]; ++z)
                        row[z] = acc.getValue(nanovdb::Coord(lo[0] + int32_t(x), lo[1] + int32_t(y),
                                                             lo[2] + int32_t(z)));
                }
        });
    return block;
}

}  // namespace mirage
