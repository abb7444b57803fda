#include "volume/grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/error.h"
#include "volume/grid_lookup.h"
#include "volume/load_progress.h"
#include "volume/stored_values.h"

namespace mirage {

namespace {

// The largest value a trilinear lookup can return. NanoVDB's node statistics cover active
// values only, but the sampler also reads inactive voxels of a leaf and inactive tiles, so
// every stored value counts: all leaf values (as decoded, at a quantised precision), all tile
// values of the internal and root nodes, and the background (what lies outside every tile).
// `leafMaximum`, when given, is the leaves' largest value, known already: only the tiles are
// read then.
template <typename Grid>
float maxStoredValue(const Grid& grid, std::optional<float> leafMaximum) {
    float m = grid.tree().background();
    auto keep = [&m](float v, uint64_t) { m = std::max(m, v); };
    if (leafMaximum) {
        m = std::max(m, *leafMaximum);
        forEachTileValue(grid.tree(), keep);
    } else if constexpr (std::is_same_v<Grid, nanovdb::FloatGrid>) {
        // A float grid's leaves are one array: their maximum on every core (a big cache's
        // leaves hold gigabytes), then the tiles.
        const auto* leaf = grid.tree().getFirstLeaf();
        m = tbb::parallel_reduce(
            tbb::blocked_range<uint32_t>(0, grid.tree().nodeCount(0), 1024), m,
            [leaf](const tbb::blocked_range<uint32_t>& r, float local) {
                for (uint32_t i = r.begin(); i != r.end(); ++i)
                    for (const float v : leaf[i].data()->mValues) local = std::max(local, v);
                return local;
            },
            [](float a, float b) { return std::max(a, b); });
        forEachTileValue(grid.tree(), keep);
    } else {
        forEachDecodedValue(grid.tree(), keep);
    }
    return m;
}

// What the constructor reads of the NanoVDB grid, at whichever precision it holds.
struct GridFacts {
    Bounds3 objectBounds;
    float minVoxelSize = 0.f, maxValue = 0.f;
    uint64_t activeVoxels = 0, leaves = 0;
};

template <typename Grid>
GridFacts gridFacts(const Grid& g, std::optional<float> leafMaximum) {
    GridFacts f;
    // A voxel at index i contributes to trilinear lookups in the open interval (i-1, i+1) on
    // each axis, so the medium is non-zero only inside the active index bbox dilated by one
    // voxel. Its 8 corners through the grid's affine index → object map bound it in object
    // space.
    const nanovdb::CoordBBox box = g.indexBBox();
    if (!box.empty()) {
        for (int c = 0; c < 8; ++c) {
            nanovdb::Vec3d corner(c & 1 ? box.max()[0] + 1.0 : box.min()[0] - 1.0,
                                  c & 2 ? box.max()[1] + 1.0 : box.min()[1] - 1.0,
                                  c & 4 ? box.max()[2] + 1.0 : box.min()[2] - 1.0);
            nanovdb::Vec3d p = g.indexToWorld(corner);
            f.objectBounds.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
    }
    const nanovdb::Vec3d voxel = g.voxelSize();
    f.minVoxelSize = float(std::min(voxel[0], std::min(voxel[1], voxel[2])));
    f.activeVoxels = g.activeVoxelCount();
    f.leaves = g.tree().nodeCount(0);
    f.maxValue = maxStoredValue(g, leafMaximum);
    return f;
}

GridPrecision precisionOf(const nanovdb::GridHandle<nanovdb::HostBuffer>& handle) {
    switch (handle.gridType()) {
        case nanovdb::GridType::Fp16:
            return GridPrecision::Half;
        case nanovdb::GridType::Fp8:
            return GridPrecision::Fp8;
        case nanovdb::GridType::Fp4:
            return GridPrecision::Fp4;
        case nanovdb::GridType::FpN:
            return GridPrecision::FpN;
        default:
            return GridPrecision::Float;
    }
}

}  // namespace

FloatGrid::FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
                     uint64_t sanitizedVoxels)
    : FloatGrid(std::move(handle), std::move(name), sanitizedVoxels, std::nullopt) {}

FloatGrid::FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
                     uint64_t sanitizedVoxels, std::optional<float> leafMaximum)
    : mHandle(std::make_shared<nanovdb::GridHandle<nanovdb::HostBuffer>>(std::move(handle))),
      mName(std::move(name)),
      mSanitized(sanitizedVoxels) {
    mPrecision = precisionOf(*mHandle);
    MIRAGE_CHECK(mPrecision != GridPrecision::Float || grid() != nullptr);
    mIndexMap = visit([](const auto& g) { return IndexMap(g.map()); });
    const GridFacts facts = visit([&](const auto& g) { return gridFacts(g, leafMaximum); });
    mObjectBounds = facts.objectBounds;
    mMinVoxelSize = facts.minVoxelSize;
    mActiveVoxels = facts.activeVoxels;
    mLeaves = facts.leaves;
    mMaxValue = facts.maxValue;
    // A quantised grid keeps no dense copy: a float copy of its box would undo the memory its
    // precision saves, and a copy at its precision would cost the decode it spares.
    if (mPrecision == GridPrecision::Float) {
        // A second at 10⁸ voxels: a stage of a big grid's load.
        LoadStage stage("dense copy of", "", "grid '" + mName + "'", treeBytes(), 1, "step");
        mDense = DenseBlock::of(*grid(), treeBytes());
        stage.advance(1);
    }
}

float FloatGrid::sampleQuantised(const Accessor& acc, const Vec3& pi) const {
    const StencilCell c(pi);
    return visit([&](const auto& g) {
        using BuildT = typename std::decay_t<decltype(g)>::BuildType;
        return sampleTree<BuildT>(acc.as<BuildT>(), c, pi);
    });
}

uint64_t FloatGrid::treeBytes() const { return mHandle ? mHandle->size() : 0; }

uint64_t FloatGrid::denseBytes() const { return mDense ? mDense->bytes() : 0; }

}  // namespace mirage
