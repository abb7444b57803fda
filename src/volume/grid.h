// A scalar volume grid in NanoVDB form: the hot-path representation every shader samples.
#pragma once

#include <memory>
#include <string>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include "core/math.h"

namespace mirage {

class FloatGrid {
public:
    using Accessor = nanovdb::FloatGrid::AccessorType;
    using Sampler = nanovdb::SampleFromVoxels<Accessor, 1, false>;  // trilinear

    FloatGrid() = default;
    FloatGrid(nanovdb::GridHandle<nanovdb::HostBuffer> handle, std::string name,
              uint64_t sanitizedVoxels = 0);

    bool valid() const { return mGrid != nullptr; }
    const std::string& name() const { return mName; }
    const nanovdb::FloatGrid* grid() const { return mGrid; }
    Accessor accessor() const { return mGrid->getAccessor(); }

    // Trilinear value at an object-space point (metres). Outside the active region the
    // background (0 for fog volumes) is returned.
    float sample(const Accessor& acc, const Vec3& pObject) const {
        nanovdb::Vec3f pi = mGrid->worldToIndexF(nanovdb::Vec3f(pObject.x, pObject.y, pObject.z));
        return nanovdb::createSampler<1, Accessor, false>(acc)(pi);
    }

    Bounds3 objectBounds() const { return mObjectBounds; }  // active voxels, dilated by 1 voxel
    // Index-space active bbox, inclusive.
    nanovdb::CoordBBox indexBounds() const { return mGrid->indexBBox(); }
    float maxValue() const { return mMaxValue; }
    uint64_t activeVoxels() const { return mGrid->activeVoxelCount(); }
    uint64_t memoryBytes() const { return mHandle ? mHandle->size() : 0; }
    uint64_t sanitizedVoxels() const { return mSanitized; }

private:
    std::shared_ptr<nanovdb::GridHandle<nanovdb::HostBuffer>> mHandle;
    const nanovdb::FloatGrid* mGrid = nullptr;
    std::string mName;
    Bounds3 mObjectBounds;
    float mMaxValue = 0.f;
    uint64_t mSanitized = 0;
};

}  // namespace mirage
