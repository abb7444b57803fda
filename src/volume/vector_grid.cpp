#include "volume/vector_grid.h"

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridStats.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "volume/grid_lookup.h"
#include "volume/stored_values.h"
#include "volume/voxel_rule.h"

namespace mirage {

namespace {

// In double: a finite float vector can have a length whose square overflows a float.
double normd(const nanovdb::Vec3f& v) {
    return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
}
float norm(const nanovdb::Vec3f& v) { return float(normd(v)); }

}  // namespace

uint64_t sanitizeVectorVoxels(nanovdb::GridHandle<nanovdb::HostBuffer>& handle, float maxMagnitude,
                              uint64_t* zeroed) {
    nanovdb::Vec3fGrid& grid = *handle.grid<nanovdb::Vec3f>();
    uint64_t changed = 0, zero = 0;
    forEachStoredValue(grid.tree(), [&](nanovdb::Vec3f& v, uint64_t voxels) {
        if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]))) {
            v = nanovdb::Vec3f(0.f);
            changed += voxels;
            zero += voxels;
            return;
        }
        const double n = normd(v);
        if (n > maxMagnitude) {
            for (int a = 0; a < 3; ++a) v[a] = float(double(v[a]) * (maxMagnitude / n));
            changed += voxels;
        }
    });
    if (changed > 0) {
        // The node statistics (min/max) and the checksum describe the old values.
        nanovdb::gridStats(grid, nanovdb::StatsMode::All);
        nanovdb::updateChecksum(grid, nanovdb::ChecksumMode::Partial);
    }
    if (zeroed) *zeroed = zero;
    return changed;
}

VectorGrid::VectorGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
                       bool staggered, uint64_t sanitizedVoxels)
    : mHandle(std::make_shared<nanovdb::GridHandle<nanovdb::HostBuffer>>(std::move(handle))),
      mName(std::move(name)),
      mStaggered(staggered),
      mSanitized(sanitizedVoxels) {
    const nanovdb::Vec3fGrid* g = grid();
    MIRAGE_CHECK(g != nullptr);
    mIndexMap = IndexMap(g->map());
    mActiveVoxels = g->activeVoxelCount();

    // A collocated voxel reaches lookups within one voxel of its centre; a staggered component
    // sits half a voxel off it, so its reach is one and a half voxels on that axis.
    const nanovdb::CoordBBox box = g->indexBBox();
    const double reach = mStaggered ? 1.5 : 1.0;
    if (!box.empty()) {
        for (int c = 0; c < 8; ++c) {
            nanovdb::Vec3d corner(c & 1 ? box.max()[0] + reach : box.min()[0] - reach,
                                  c & 2 ? box.max()[1] + reach : box.min()[1] - reach,
                                  c & 4 ? box.max()[2] + reach : box.min()[2] - reach);
            nanovdb::Vec3d p = g->indexToWorld(corner);
            mObjectBounds.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
    }

    // Bounds over every stored value (the stencil reads inactive ones too); the range of |v|
    // over the active voxels, for reports.
    auto& tree = const_cast<nanovdb::Vec3fGrid*>(g)->tree();
    nanovdb::Vec3f componentMax(0.f);
    forEachStoredValue(tree, [&](nanovdb::Vec3f& v, uint64_t) {
        mMagnitudeBound = std::max(mMagnitudeBound, norm(v));
        for (int a = 0; a < 3; ++a) componentMax[a] = std::max(componentMax[a], std::abs(v[a]));
    });
    if (mStaggered) mMagnitudeBound = norm(componentMax);
    mComponentBound = Vec3(componentMax[0], componentMax[1], componentMax[2]);
    mMinMagnitude = kInfinity;
    const auto* leaf = g->tree().getFirstLeaf();
    for (uint32_t i = 0; i < g->tree().nodeCount(0); ++i)
        for (auto on = leaf[i].valueMask().beginOn(); on; ++on) {
            const float n = norm(leaf[i].getValue(*on));
            mMaxMagnitude = std::max(mMaxMagnitude, n);
            mMinMagnitude = std::min(mMinMagnitude, n);
        }
    if (mMinMagnitude > mMaxMagnitude) mMinMagnitude = mMaxMagnitude = 0.f;
}

namespace {

using Leaf = nanovdb::NanoLeaf<nanovdb::Vec3f>;

// Trilinear, bit for bit NanoVDB's SampleFromVoxels<1>, with the leaf fast path of the density
// lookups (volume/leaf_stencil.h).
Vec3 sampleCollocated(const VectorGrid::Accessor& acc, const nanovdb::Vec3f& pi) {
    const float fi[3] = {std::floor(pi[0]), std::floor(pi[1]), std::floor(pi[2])};
    const nanovdb::Coord b{int32_t(fi[0]), int32_t(fi[1]), int32_t(fi[2])};
    constexpr int kStencil[3] = {1, 1, 1};
    nanovdb::Vec3f v;
    if (const Leaf* leaf = leafHoldingBox<Leaf>(acc, b, kStencil)) {
        const float u[3] = {pi[0] - fi[0], pi[1] - fi[1], pi[2] - fi[2]};
        v = trilinearInLeaf(*leaf, Leaf::CoordToOffset(b), u);
    } else {
        v = nanovdb::createSampler<1, VectorGrid::Accessor::Base, false>(acc)(pi);
    }
    return {v[0], v[1], v[2]};
}

// Component a is stored at index position (i − ½ e_a): its lattice coordinate is pi + ½ e_a,
// and its cell floor(pi + ½ e_a) is the cell b = floor(pi) or the next one along a (when the
// fraction of pi along a is ½ or more). So the three components' stencils lie in the box of
// b's 2×2×2 voxels grown by one along each axis whose component needs it: 8 to 27 voxel reads,
// 15.6 on average, read once each, instead of three trilinear lookups of 8 (Mantaflow's
// blurred lookups spent most of their extra time there, docs/scene-file.md "Motion blur");
// from the leaf's array when one leaf holds the box (about half the lookups), as the density
// lookups do.
Vec3 sampleStaggered(const VectorGrid::Accessor& acc, const nanovdb::Vec3f& pi) {
    const nanovdb::Coord b = nanovdb::RoundDown<nanovdb::Coord>(pi);
    float frac[3];
    int shift[3];
    for (int a = 0; a < 3; ++a) {
        frac[a] = pi[a] - float(b[a]);
        shift[a] = frac[a] >= 0.5f ? 1 : 0;
    }
    nanovdb::Vec3f v[3][3][3];
    const int extent[3] = {1 + shift[0], 1 + shift[1], 1 + shift[2]};
    if (const Leaf* leaf = leafHoldingBox<Leaf>(acc, b, extent)) {
        const uint32_t o = Leaf::CoordToOffset(b);
        for (int i = 0; i <= extent[0]; ++i)
            for (int j = 0; j <= extent[1]; ++j)
                for (int k = 0; k <= extent[2]; ++k)
                    v[i][j][k] = leaf->getValue(o + leafStep<Leaf>(i, j, k));
    } else {
        for (int i = 0; i <= extent[0]; ++i)
            for (int j = 0; j <= extent[1]; ++j)
                for (int k = 0; k <= extent[2]; ++k)
                    v[i][j][k] = acc.getValue(b + nanovdb::Coord(i, j, k));
    }
    float out[3];
    for (int a = 0; a < 3; ++a) {
        // Component a's cell origin (offset from b) and weights: along a its lattice is half a
        // voxel behind the centres, along the other axes it is theirs.
        int o[3] = {0, 0, 0};
        float w[3] = {frac[0], frac[1], frac[2]};
        o[a] = shift[a];
        w[a] = frac[a] + 0.5f - float(shift[a]);
        auto at = [&](int i, int j, int k) { return v[o[0] + i][o[1] + j][o[2] + k][a]; };
        auto lerp1 = [](float t, float x0, float x1) { return x0 + t * (x1 - x0); };
        const float x00 = lerp1(w[2], at(0, 0, 0), at(0, 0, 1));
        const float x01 = lerp1(w[2], at(0, 1, 0), at(0, 1, 1));
        const float x10 = lerp1(w[2], at(1, 0, 0), at(1, 0, 1));
        const float x11 = lerp1(w[2], at(1, 1, 0), at(1, 1, 1));
        out[a] = lerp1(w[0], lerp1(w[1], x00, x01), lerp1(w[1], x10, x11));
    }
    return {out[0], out[1], out[2]};
}

}  // namespace

uint64_t VectorGrid::memoryBytes() const { return mHandle ? mHandle->size() : 0; }

Vec3 VectorGrid::sample(const Accessor& acc, const Vec3& pObject) const {
    const Vec3 p = mIndexMap.toIndex(pObject);
    const nanovdb::Vec3f pi(p.x, p.y, p.z);
    return mStaggered ? sampleStaggered(acc, pi) : sampleCollocated(acc, pi);
}

}  // namespace mirage
