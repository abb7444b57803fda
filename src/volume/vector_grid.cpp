#include "volume/vector_grid.h"

#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/GridStats.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "volume/stored_values.h"

namespace mirage {

namespace {

// In double: a finite float vector can have a length whose square overflows a float.
double normd(const nanovdb::Vec3f& v) {
    return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
}
float norm(const nanovdb::Vec3f& v) { return float(normd(v)); }

}  // namespace

uint64_t sanitizeVectorVoxels(nanovdb::Vec3fGrid& grid, float maxMagnitude, uint64_t* zeroed) {
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
    mGrid = mHandle->grid<nanovdb::Vec3f>();
    MIRAGE_CHECK(mGrid != nullptr);

    // A collocated voxel reaches lookups within one voxel of its centre; a staggered component
    // sits half a voxel off it, so its reach is one and a half voxels on that axis.
    const nanovdb::CoordBBox box = mGrid->indexBBox();
    const double reach = mStaggered ? 1.5 : 1.0;
    if (!box.empty()) {
        for (int c = 0; c < 8; ++c) {
            nanovdb::Vec3d corner(c & 1 ? box.max()[0] + reach : box.min()[0] - reach,
                                  c & 2 ? box.max()[1] + reach : box.min()[1] - reach,
                                  c & 4 ? box.max()[2] + reach : box.min()[2] - reach);
            nanovdb::Vec3d p = mGrid->indexToWorld(corner);
            mObjectBounds.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
    }

    // Bounds over every stored value (the stencil reads inactive ones too); the range of |v|
    // over the active voxels, for reports.
    auto& tree = const_cast<nanovdb::Vec3fGrid*>(mGrid)->tree();
    nanovdb::Vec3f componentMax(0.f);
    forEachStoredValue(tree, [&](nanovdb::Vec3f& v, uint64_t) {
        mMagnitudeBound = std::max(mMagnitudeBound, norm(v));
        for (int a = 0; a < 3; ++a) componentMax[a] = std::max(componentMax[a], std::abs(v[a]));
    });
    if (mStaggered) mMagnitudeBound = norm(componentMax);
    mComponentBound = Vec3(componentMax[0], componentMax[1], componentMax[2]);
    mMinMagnitude = kInfinity;
    const auto* leaf = mGrid->tree().getFirstLeaf();
    for (uint32_t i = 0; i < mGrid->tree().nodeCount(0); ++i)
        for (auto on = leaf[i].valueMask().beginOn(); on; ++on) {
            const float n = norm(leaf[i].getValue(*on));
            mMaxMagnitude = std::max(mMaxMagnitude, n);
            mMinMagnitude = std::min(mMinMagnitude, n);
        }
    if (mMinMagnitude > mMaxMagnitude) mMinMagnitude = mMaxMagnitude = 0.f;
}

Vec3 VectorGrid::sample(const Accessor& acc, const Vec3& pObject) const {
    const nanovdb::Vec3f pi = mGrid->worldToIndexF(nanovdb::Vec3f(pObject.x, pObject.y, pObject.z));
    auto trilinear = nanovdb::createSampler<1, Accessor, false>(acc);
    if (!mStaggered) {
        const nanovdb::Vec3f v = trilinear(pi);
        return {v[0], v[1], v[2]};
    }
    // Component a is stored at index position (i − ½ e_a): its lattice coordinate is pi + ½ e_a.
    return {trilinear(pi + nanovdb::Vec3f(0.5f, 0.f, 0.f))[0],
            trilinear(pi + nanovdb::Vec3f(0.f, 0.5f, 0.f))[1],
            trilinear(pi + nanovdb::Vec3f(0.f, 0.f, 0.5f))[2]};
}

}  // namespace mirage
