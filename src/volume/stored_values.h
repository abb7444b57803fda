// Every value a NanoVDB tree stores, for the passes that must see all of them: the voxel rules
// (a NaN anywhere poisons lookups) and the bounds of what a lookup can return. The trilinear
// stencil reads inactive leaf voxels and tiles as well as active voxels, so all of them count.
#pragma once

#include <cstdint>

namespace mirage {

// Calls f(value, voxels) on every stored value of `tree`: leaf voxels (active and inactive),
// then the tiles of the lower, upper and root nodes with the number of voxels each covers
// (8³, 128³, 4096³). `value` is a reference: f may change it.
template <typename Tree, typename F>
void forEachStoredValue(Tree& tree, F&& f) {
    auto* leaf = tree.getFirstLeaf();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i)
        for (auto& v : leaf[i].data()->mValues) f(v, uint64_t(1));
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

}  // namespace mirage
