// The inside of a closed shape as a Region (core/region.h): what a medium bound to the shape
// (`interior_medium`) is confined to. Spheres answer analytically; closed triangle meshes by
// counting crossings (Jordan: a point is inside a closed surface when a ray from it crosses the
// surface an odd number of times), with an Embree BVH of the mesh's own triangles.
#pragma once

#include <memory>
#include <vector>

#include "core/region.h"

namespace mirage {

std::shared_ptr<const Region> makeSphereRegion(const Vec3& center, float radius);
// World-space triangles (3 indices each) of a closed, consistently wound mesh. Throws
// MirageError on an Embree error.
std::shared_ptr<const Region> makeMeshRegion(std::vector<Vec3> positions,
                                             std::vector<uint32_t> indices);

}  // namespace mirage
