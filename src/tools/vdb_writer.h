// Writing OpenVDB files, for the translation units that build OpenVDB grids themselves: the
// procedural assets (asset_writer.cpp) and the hand-specified grids of the tests. Includes
// OpenVDB: include it only where OpenVDB is already needed.
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <string>

#include "core/math.h"

namespace mirage {

// openvdb::initialize(), once per process.
void initOpenVdb();

// The file compression flags of "blosc" (falls back to zip when this OpenVDB lacks Blosc),
// "zip" or "none"; throws MirageError naming `path` for another name. OpenVDB never zips fog
// volumes and level sets, so zip reaches only grids of class "unknown".
uint32_t vdbCompressionFlags(const std::string& name, const std::string& path);

// Writes the grids and the file metadata to `path` atomically (core/atomic_file.h), reading the
// file back before the rename (a full disk can truncate a write without OpenVDB noticing).
// Throws MirageError naming `path` when its folder is missing or the write fails.
void writeVdbFile(const std::string& path, const openvdb::GridPtrVec& grids,
                  const openvdb::MetaMap& meta, const std::string& compression);

// A uniform-scale linear transform: voxel size `voxelSize` (m), index (0,0,0) at `origin`.
openvdb::math::Transform::Ptr linearVdbTransform(double voxelSize, const Vec3d& origin);

}  // namespace mirage
