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
//
// Like volume/grid.h, this header names no NanoVDB type: the accessor and the NanoVDB grid are
// in volume/grid_lookup.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/math.h"
#include "volume/index_map.h"
#include "volume/nanovdb_fwd.h"

namespace mirage {

class VectorGrid {
public:
    // A thread's cached path through the tree (volume/grid_lookup.h).
    class Accessor;

    VectorGrid() = default;
    VectorGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name, bool staggered,
               uint64_t sanitizedVoxels = 0);

    bool valid() const { return mHandle != nullptr; }
    const std::string& name() const { return mName; }
    bool staggered() const { return mStaggered; }
    // The NanoVDB grid (a const nanovdb::Vec3fGrid*) and a new accessor of it.
    inline const auto* grid() const;
    inline Accessor accessor() const;

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
    // Index-space active bbox, inclusive (a nanovdb::CoordBBox).
    inline auto indexBounds() const;
    uint64_t activeVoxels() const { return mActiveVoxels; }
    uint64_t memoryBytes() const;
    uint64_t sanitizedVoxels() const { return mSanitized; }

private:
    std::shared_ptr<nanovdb::GridHandle<nanovdb::HostBuffer>> mHandle;
    IndexMap mIndexMap;  // object → index space (volume/index_map.h)
    std::string mName;
    bool mStaggered = false;
    Bounds3 mObjectBounds;
    float mMagnitudeBound = 0.f, mMaxMagnitude = 0.f, mMinMagnitude = 0.f;
    Vec3 mComponentBound;
    uint64_t mActiveVoxels = 0;
    uint64_t mSanitized = 0;
};

}  // namespace mirage
