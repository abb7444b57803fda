// A 3-vector volume grid in NanoVDB form (velocity): collocated or staggered.
//
// Simulators store velocity two ways. Houdini's `vel` is collocated: the vector of voxel
// (i, j, k) is the velocity at the voxel's centre. Mantaflow and other MAC-grid solvers write a
// staggered (face-centred) grid, OpenVDB class GRID_STAGGERED: the x component stored at voxel
// (i, j, k) is the flux through the face between voxels i−1 and i, at index position
// (i − ½, j, k); likewise y at (i, j − ½, k) and z at (i, j, k − ½) (Harlow & Welch 1965, the
// marker-and-cell grid). A staggered lookup therefore interpolates each component trilinearly
// on its own lattice, shifted by half a voxel along its axis; reading the vectors as if they
// were centred would displace every component by half a voxel.
#pragma once

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>

#include <memory>
#include <string>

#include "core/math.h"
#include "volume/index_map.h"

namespace mirage {

class VectorGrid {
public:
    using Accessor = nanovdb::Vec3fGrid::AccessorType;

    VectorGrid() = default;
    VectorGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name, bool staggered,
               uint64_t sanitizedVoxels = 0);

    bool valid() const { return mGrid != nullptr; }
    const std::string& name() const { return mName; }
    bool staggered() const { return mStaggered; }
    const nanovdb::Vec3fGrid* grid() const { return mGrid; }
    Accessor accessor() const { return mGrid->getAccessor(); }

    // The vector at an object-space point (metres), in the grid's units; 0 outside the
    // active region (a velocity background is 0).
    Vec3 sample(const Accessor& acc, const Vec3& pObject) const;

    // An upper bound of |sample()| anywhere: the largest stored |v| for a collocated grid
    // (trilinear weights are convex), the norm of the per-component maxima for a staggered
    // one (each component is a convex combination on its own lattice).
    float magnitudeBound() const { return mMagnitudeBound; }
    // Per axis, the largest |v_a| stored: bounds |sample().a| (each component of a lookup is a
    // convex combination of stored components, staggered or not).
    Vec3 componentBound() const { return mComponentBound; }
    // The largest and smallest |v| over the active leaf voxels (for `mirage info`).
    float maxMagnitude() const { return mMaxMagnitude; }
    float minMagnitude() const { return mMinMagnitude; }

    Bounds3 objectBounds() const { return mObjectBounds; }
    nanovdb::CoordBBox indexBounds() const { return mGrid->indexBBox(); }
    uint64_t activeVoxels() const { return mGrid->activeVoxelCount(); }
    uint64_t memoryBytes() const { return mHandle ? mHandle->size() : 0; }
    uint64_t sanitizedVoxels() const { return mSanitized; }

private:
    std::shared_ptr<nanovdb::GridHandle<nanovdb::HostBuffer>> mHandle;
    const nanovdb::Vec3fGrid* mGrid = nullptr;
    IndexMap mIndexMap;  // object → index space (volume/index_map.h)
    std::string mName;
    bool mStaggered = false;
    Bounds3 mObjectBounds;
    float mMagnitudeBound = 0.f, mMaxMagnitude = 0.f, mMinMagnitude = 0.f;
    Vec3 mComponentBound;
    uint64_t mSanitized = 0;
};

// The voxel rule for vectors, applied to every stored value (leaf voxels, active or not, and
// tiles): a vector with a NaN or infinite component becomes 0 (it would poison every lookup
// that reads it), and one longer than `maxMagnitude` is shortened to that length, direction
// kept. Returns the number of voxels changed (a tile counts all of its voxels); *zeroed, when
// given, receives how many of them were zeroed.
uint64_t sanitizeVectorVoxels(nanovdb::Vec3fGrid& grid, float maxMagnitude,
                              uint64_t* zeroed = nullptr);

}  // namespace mirage
