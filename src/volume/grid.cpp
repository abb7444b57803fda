#include "volume/grid.h"

#include <algorithm>
#include <utility>

#include "core/error.h"
#include "volume/grid_lookup.h"
#include "volume/stored_values.h"

namespace mirage {

namespace {

// The largest value a trilinear lookup can return. NanoVDB's node statistics cover active
// values only, but the sampler also reads inactive voxels of a leaf and inactive tiles, so
// every stored value counts: all leaf values, all tile values of the internal and root nodes,
// and the background (what lies outside every tile).
float maxStoredValue(const nanovdb::FloatGrid& grid) {
    float m = grid.tree().background();
    forEachStoredValue(grid.tree(), [&m](const float& v, uint64_t) { m = std::max(m, v); });
    return m;
}

}  // namespace

FloatGrid::FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
                     uint64_t sanitizedVoxels)
    : mHandle(std::make_shared<nanovdb::GridHandle<nanovdb::HostBuffer>>(std::move(handle))),
      mName(std::move(name)),
      mSanitized(sanitizedVoxels) {
    const nanovdb::FloatGrid* g = grid();
    MIRAGE_CHECK(g != nullptr);
    mIndexMap = IndexMap(g->map());

    // A voxel at index i contributes to trilinear lookups in the open interval (i-1, i+1) on
    // each axis, so the medium is non-zero only inside the active index bbox dilated by one
    // voxel. Its 8 corners through the grid's affine index → object map bound it in object space.
    const nanovdb::CoordBBox box = g->indexBBox();
    if (!box.empty()) {
        for (int c = 0; c < 8; ++c) {
            nanovdb::Vec3d corner(c & 1 ? box.max()[0] + 1.0 : box.min()[0] - 1.0,
                                  c & 2 ? box.max()[1] + 1.0 : box.min()[1] - 1.0,
                                  c & 4 ? box.max()[2] + 1.0 : box.min()[2] - 1.0);
            nanovdb::Vec3d p = g->indexToWorld(corner);
            mObjectBounds.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
    }
    const nanovdb::Vec3d voxel = g->voxelSize();
    mMinVoxelSize = float(std::min(voxel[0], std::min(voxel[1], voxel[2])));
    mActiveVoxels = g->activeVoxelCount();
    mMaxValue = maxStoredValue(*g);
    mDense = DenseBlock::of(*g, treeBytes());
}

uint64_t FloatGrid::treeBytes() const { return mHandle ? mHandle->size() : 0; }

uint64_t FloatGrid::denseBytes() const { return mDense ? mDense->bytes() : 0; }

}  // namespace mirage
