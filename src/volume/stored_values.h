// Every value a NanoVDB tree stores, for the passes that must see all of them: the voxel rules
// (a NaN anywhere poisons lookups) and the bounds of what a lookup can return. The trilinear
// stencil reads inactive leaf voxels and tiles as well as active voxels, so all of them count.
#pragma once

#include <cstdint>
#include <type_traits>

namespace mirage {

// Calls f(value, voxels) on every tile value of `tree`: the tiles of the lower, upper and root
// nodes with the number of voxels each covers (8³, 128³, 4096³). Tiles are float at every
// precision (volume/grid_precision.h). `value` is a reference: f may change it.
template <typename Tree, typename F>
void forEachTileValue(Tree& tree, F&& f) {
    auto* lower = tree.getFirstLower();
    for (uint32_t i = 0; i < tree.nodeCount(1); ++i)
        for (uint32_t n = 0; n < 4096; ++n)
            if (!lower[i].data()->isChild(n)) f(lower[i].data()->mTable[n].value, uint64_t(512));
    auto* upper = tree.getFirstUpper();
    for (uint32_t i = 0; i < tree.nodeCount(2); ++i)
        for (uint32_t n = 0; n < 32768; ++n)
            if (!upper[i].data()->isChild(n))
                f(upper[i].data()->mTable[n].value, uint64_t(128) * 128 * 128);
    auto* root = tree.root().data();
    for (uint32_t t = 0; t < root->mTableSize; ++t)
        if (!root->tile(t)->isChild()) f(root->tile(t)->value, uint64_t(4096) * 4096 * 4096);
}

// Calls f(leaf) on every leaf of `tree`, through its lower nodes' children: fpn leaves vary in
// size (volume/grid_precision.h), so they cannot be indexed as an array from the first one.
template <typename Tree, typename F>
void forEachLeaf(const Tree& tree, F&& f) {
    const auto* lower = tree.getFirstLower();
    for (uint32_t i = 0; i < tree.nodeCount(1); ++i)
        for (uint32_t n = 0; n < 4096; ++n)
            if (lower[i].data()->isChild(n)) f(*lower[i].data()->getChild(n));
}

// Calls f(value, voxels) on every stored value of a float `tree`: leaf voxels (active and
// inactive), then the tiles. `value` is a reference: f may change it.
template <typename Tree, typename F>
void forEachStoredValue(Tree& tree, F&& f) {
    auto* leaf = tree.getFirstLeaf();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i)
        for (auto& v : leaf[i].data()->mValues) f(v, uint64_t(1));
    forEachTileValue(tree, f);
}

// The same, read-only, for a tree at any precision: leaf voxels as a lookup decodes them.
template <typename Tree, typename F>
void forEachDecodedValue(const Tree& tree, F&& f) {
    forEachLeaf(tree, [&f](const auto& leaf) {
        for (uint32_t n = 0; n < 512; ++n) f(float(leaf.getValue(n)), uint64_t(1));
    });
    forEachTileValue(tree, [&f](const auto& v, uint64_t voxels) { f(float(v), voxels); });
}

// A leaf's 512 values as a lookup reads them: a float leaf's own array, else decoded into buf.
template <typename Leaf>
const float* leafValues(const Leaf& leaf, float* buf) {
    if constexpr (std::is_same_v<typename Leaf::BuildType, float>) {
        return leaf.data()->mValues;
    } else {
        for (uint32_t n = 0; n < 512; ++n) buf[n] = leaf.getValue(n);
        return buf;
    }
}

}  // namespace mirage
