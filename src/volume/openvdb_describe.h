// How a grid's numbers read in messages and in `mirage info`: a value or a vector at six
// significant digits (one number where its three components agree), a grid's transform in
// words. Included by volume/vdb_file.cpp alone: it brings OpenVDB's headers, which cost ~28 s
// and ~1 GB per translation unit (docs/design.md, "Headers").
#pragma once

#include <openvdb/openvdb.h>

#include <sstream>
#include <string>

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

}  // namespace mirage::vdbtext
