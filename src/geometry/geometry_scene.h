// The surfaces of a scene: an Embree 3 BVH over triangle meshes (OBJ files, quads as two
// triangles) and analytic spheres (Embree user geometry, intersected in double precision), with
// a material per shape. Integrators ask two questions of it: the nearest surface along a ray
// (intersect) and whether any surface blocks a segment (occluded, for shadow rays).
//
// A closed shape (sphere or closed mesh) may bound a medium: `interiorMedium` names the scene
// medium placed inside it, and interiorRegion() gives the shape's inside, to which the scene
// stage confines that medium and cuts out of every other medium (medium/confinement.h).
// Every surface, glass included, blocks shadow rays:
// light through specular surfaces (caustics) comes from the photon map.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/region.h"
#include "core/surface_epsilon.h"
#include "core/transform.h"
#include "geometry/material.h"

namespace mirage {

struct SurfaceHit {
    float t;        // ray parameter (m)
    Vec3 p;         // world position
    Vec3 ns;        // shading normal (unit, on the side of ng)
    Vec3 ng;        // geometric normal (unit; outward for spheres, edge_u × edge_v for quads,
                    // counter-clockwise winding for meshes)
    int material;   // index into GeometryScene::material
    int shape;      // index into GeometryScene::shape
};

// A triangle mesh in object space; normals per vertex (optional, same count as positions).
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<Vec3> normals;
};

// Reads the triangles of every object in an OBJ file (polygons are triangulated); vertex
// normals are kept when every face has them. Throws MirageError naming the file.
TriangleMesh loadObjMesh(const std::string& path);

enum class ShapeType { Mesh, Sphere, Quad };

struct ShapeInfo {
    ShapeType type = ShapeType::Mesh;
    int material = 0;
    int interiorMedium = -1;  // index of the scene medium inside the shape, −1 for none
    // A holdout ([[shape]] holdout = true): it occludes and casts shadows, but the camera sees
    // it black with zero alpha, so that a render comps over a plate holding the real object.
    bool holdout = false;
    std::string name;  // [[shape]] name: what Cryptomatte calls it (film/cryptomatte.h)
    Bounds3 bounds;
    size_t triangles = 0;
    // Sphere: centre and radius; quad: corner and edges (world).
    Vec3 center, edgeU, edgeV;
    float radius = 0.f;
};

class GeometryScene {
public:
    GeometryScene();
    ~GeometryScene();
    GeometryScene(const GeometryScene&) = delete;
    GeometryScene& operator=(const GeometryScene&) = delete;

    int addMaterial(Material m);
    // Each returns the shape's index. The transform places object-space meshes in the world.
    int addMesh(const TriangleMesh& mesh, const Transform& objectToWorld, int material,
                int interiorMedium = -1);
    int addSphere(const Vec3& center, float radius, int material, int interiorMedium = -1);
    // The parallelogram corner + s·edgeU + t·edgeV, s, t ∈ [0, 1]; normal edgeU × edgeV.
    int addQuad(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV, int material,
                int interiorMedium = -1);
    // Builds the BVH; call once after the last add. Throws MirageError on an Embree error.
    void commit();

    bool empty() const { return mShapes.empty(); }
    size_t shapeCount() const { return mShapes.size(); }
    size_t materialCount() const { return mMaterials.size(); }
    const ShapeInfo& shape(int i) const { return mShapes[size_t(i)]; }
    const Material& material(int i) const { return mMaterials[size_t(i)]; }
    const Material& materialAt(const SurfaceHit& h) const { return material(h.material); }
    void setHoldout(int shape, bool holdout) { mShapes[size_t(shape)].holdout = holdout; }
    void setName(int shape, std::string name) { mShapes[size_t(shape)].name = std::move(name); }
    bool holdout(const SurfaceHit& h) const { return mShapes[size_t(h.shape)].holdout; }
    Bounds3 bounds() const { return mBounds; }
    double buildSeconds() const { return mBuildSeconds; }

    // The inside of shape i (a sphere or a closed mesh; null for a quad).
    std::shared_ptr<const Region> interiorRegion(int shape) const;

    // Nearest surface along ray (unit direction) in (0, ray.tMax).
    std::optional<SurfaceHit> intersect(const Ray& ray) const;
    // Distance (m) from o along the unit direction d to the nearest surface, +∞ for none (the
    // curved paths' step cap near surfaces, transport/surface_step_cap.h).
    double surfaceDistance(const Vec3d& o, const Vec3d& d) const {
        const auto hit = intersect(Ray{Vec3(o), Vec3(d)});
        return hit ? double(hit->t) : std::numeric_limits<double>::infinity();
    }
    // True when a surface lies on the segment p + t·dir, t ∈ (0, tMax).
    bool occluded(const Vec3& p, const Vec3& dir, float tMax) const;

private:
    struct Embree;
    struct SphereData {
        Vec3 center;
        float radius;
    };
    struct TriangleData {
        std::vector<Vec3> positions, normals;
        std::vector<uint32_t> indices;
    };
    int addTriangles(TriangleData data, ShapeInfo info);

    std::unique_ptr<Embree> mEmbree;
    std::vector<Material> mMaterials;
    std::vector<ShapeInfo> mShapes;
    // Per shape (by Embree geometry ID = shape index): its own data for the hit's normals.
    std::vector<std::unique_ptr<SphereData>> mSpheres;
    std::vector<std::unique_ptr<TriangleData>> mTriangles;
    Bounds3 mBounds;
    double mBuildSeconds = 0;
    bool mCommitted = false;
};

// A ray leaving a surface hit along dir, its origin pushed off the surface to dir's side by a
// few ulps of the position's magnitude, so that it does not hit the surface it starts on.
Ray spawnRay(const SurfaceHit& hit, const Vec3& dir, float tMax = kInfinity);

}  // namespace mirage
