// How a grid's numbers read in messages and in `mirage info`: a value or a vector at six
// significant digits (one number where its three components agree), a grid's transform in
// words, a NanoVDB file's grid from its metadata. Included by volume/vdb_file.cpp alone: it brings
// OpenVDB's headers, which cost ~28 s and ~1 GB per translation unit (docs/design.md, "Headers").
#pragma once

#include <openvdb/openvdb.h>

#include <sstream>
#include <string>

#include "volume/vdb_file.h"
#include "volume/vdb_format.h"

namespace mirage::vdbtext {

inline std::string fmt(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

inline std::string fmt(const openvdb::Vec3d& v) {
    if (v[0] == v[1] && v[1] == v[2]) return fmt(v[0]);
    return "(" + fmt(v[0]) + ", " + fmt(v[1]) + ", " + fmt(v[2]) + ")";
}

// "voxel size 0.476 m, index (0,0,0) at (-34, -13.1, -26.4) m", plus the map's kind when it
// rotates or shears.
inline std::string describeTransform(const openvdb::math::Transform& xform) {
    const auto map = xform.baseMap();
    if (!map->isLinear()) return map->type() + " (not affine)";
    const openvdb::Mat4d m = map->getAffineMap()->getMat4();
    bool axisAligned = true;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) axisAligned = axisAligned && (r == c || m(r, c) == 0.0);
    std::string s = axisAligned ? "" : "affine (rotated or sheared), ";
    s += "voxel size " + fmt(xform.voxelSize()) + " m, index (0,0,0) at (" + fmt(m(3, 0)) + ", " +
         fmt(m(3, 1)) + ", " + fmt(m(3, 2)) + ") m";
    return s;
}

// A NanoVDB file's grid as `mirage info` lists it, from the file's own metadata: nothing read.
inline GridInfo nanoVdbGridInfo(const vdbformat::GridRecord& record) {
    GridInfo info;
    info.name = record.name;
    info.valueType = vdbformat::valueTypeOf(record);
    info.gridClass = vdbformat::nanoClassName(record.nanoGridClass);
    info.voxelSize =
        Vec3d(record.nanoVoxelSize[0], record.nanoVoxelSize[1], record.nanoVoxelSize[2]);
    info.activeVoxels = record.nanoVoxelCount;
    info.memoryBytes = record.nanoGridBytes;
    info.compression = vdbformat::compressionName(record.compression, vdbformat::Format::NanoVdb);
    info.transform = "voxel size " +
                     fmt(openvdb::Vec3d(info.voxelSize.x, info.voxelSize.y, info.voxelSize.z)) +
                     " m (NanoVDB file metadata)";
    const int32_t* b = record.nanoIndexBBox;
    if (info.activeVoxels > 0 && b[0] <= b[3] && b[1] <= b[4] && b[2] <= b[5]) {
        for (int a = 0; a < 3; ++a) {
            info.indexMin[a] = b[a];
            info.indexMax[a] = b[a + 3];
        }
        // NanoVDB's world bbox maps [min, max + 1] (voxel corners at integer coordinates);
        // shifting by half a voxel gives the ±½ extent around voxel centres used above.
        for (int a = 0; a < 3; ++a) {
            double h = 0.5 * record.nanoVoxelSize[a];
            info.objectBounds.lo[a] = float(record.nanoWorldBBox[a] - h);
            info.objectBounds.hi[a] = float(record.nanoWorldBBox[a + 3] - h);
        }
    }
    return info;
}

}  // namespace mirage::vdbtext
