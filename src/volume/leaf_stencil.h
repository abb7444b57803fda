// The leaf fast path of the volume lookups: a trilinear (or staggered) stencil that lies inside
// one 8³ leaf node is read from the leaf's value array at fixed offsets, the leaf found once,
// instead of one accessor lookup per voxel (each compares the cached keys of three tree levels).
// Scalar density lookups and vector velocity lookups share it (volume/grid.h,
// volume/vector_grid.cpp).
#pragma once

#include <nanovdb/NanoVDB.h>

namespace mirage {

// The leaf that holds every voxel of the box [b, b + extent] (inclusive, extent ≥ 0 per axis),
// or null when the box crosses a leaf's edge or lies in a tile (then the caller reads through
// the accessor, which also returns tile and background values).
template <typename Leaf, typename Accessor>
const Leaf* leafHoldingBox(const Accessor& acc, const nanovdb::Coord& b, const int extent[3]) {
    constexpr int32_t kMask = int32_t(Leaf::DIM) - 1;
    for (int a = 0; a < 3; ++a)
        if ((b[a] & kMask) + extent[a] > kMask) return nullptr;
    return acc.probeLeaf(b);
}

// Offset within a leaf of the voxel (i, j, k) steps from the voxel at offset o: 8³ leaves store
// x-major, offset x·64 + y·8 + z.
template <typename Leaf>
constexpr uint32_t leafStep(int i, int j, int k) {
    static_assert(Leaf::LOG2DIM == 3, "8³ leaves: offsets x·64 + y·8 + z");
    return uint32_t(i) * 64u + uint32_t(j) * 8u + uint32_t(k);
}

// Trilinear interpolation of the 2×2×2 voxels v(i, j, k) (i, j, k ∈ {0, 1}) at fractions u (0 to
// 1 per axis): the lerps of NanoVDB's TrilinearSampler in its order, so the value has the same
// bits as a lookup through the accessor. ValueT is float or nanovdb::Vec3f (component by
// component).
template <typename ValueT, typename V>
ValueT trilinearStencil(const V& v, const float u[3]) {
    auto lerp = [](const ValueT& a, const ValueT& b, float w) { return a + ValueT(w) * (b - a); };
    const ValueT x0 =
        lerp(lerp(v(0, 0, 0), v(0, 0, 1), u[2]), lerp(v(0, 1, 0), v(0, 1, 1), u[2]), u[1]);
    const ValueT x1 =
        lerp(lerp(v(1, 0, 0), v(1, 0, 1), u[2]), lerp(v(1, 1, 0), v(1, 1, 1), u[2]), u[1]);
    return lerp(x0, x1, u[0]);
}

// The stencil from offset o of `leaf`.
template <typename Leaf>
typename Leaf::ValueType trilinearInLeaf(const Leaf& leaf, uint32_t o, const float u[3]) {
    auto v = [&](int i, int j, int k) { return leaf.getValue(o + leafStep<Leaf>(i, j, k)); };
    return trilinearStencil<typename Leaf::ValueType>(v, u);
}

}  // namespace mirage
