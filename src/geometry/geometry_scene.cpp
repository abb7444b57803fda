#include "geometry/geometry_scene.h"

#include <embree3/rtcore.h>

#include <cstring>

#include "core/clock.h"
#include "core/error.h"
#include "geometry/embree_commit.h"
#include "geometry/embree_ray.h"
#include "geometry/shape_region.h"

namespace mirage {

// The Embree objects. Embree reports errors through one device callback rather than return
// codes; the first message is kept and becomes a MirageError once the build is done.
struct GeometryScene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string error;

    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

void onEmbreeError(void* user, RTCError code, const char* message) {
    auto* error = static_cast<std::string*>(user);
    if (error->empty())
        *error = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

struct Sphere {
    Vec3 center;
    float radius;
};

void sphereBounds(const RTCBoundsFunctionArguments* args) {
    const auto* s = static_cast<const Sphere*>(args->geometryUserPtr);
    RTCBounds* b = args->bounds_o;
    b->lower_x = s->center.x - s->radius;
    b->lower_y = s->center.y - s->radius;
    b->lower_z = s->center.z - s->radius;
    b->upper_x = s->center.x + s->radius;
    b->upper_y = s->center.y + s->radius;
    b->upper_z = s->center.z + s->radius;
}

// Nearest root of |o + t d − c|² = r² in (tNear, tFar), in double: a float discriminant loses
// the near root to cancellation when the sphere is small and far away. Returns −1 for none.
double sphereRoot(const Sphere& s, const Vec3& o, const Vec3& d, double tNear, double tFar) {
    Vec3d oc = Vec3d(o) - Vec3d(s.center), dd(d);
    double a = dot(dd, dd), b = dot(oc, dd), c = dot(oc, oc) - double(s.radius) * s.radius;
    double disc = b * b - a * c;
    if (disc < 0.0) return -1.0;
    double sq = std::sqrt(disc);
    // Stable pair of roots: q = −(b + sign(b)√disc), t = q/a and c/q.
    double q = b > 0.0 ? -(b + sq) : -(b - sq);
    double t0 = q / a, t1 = q != 0.0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tNear && t0 < tFar) return t0;
    if (t1 > tNear && t1 < tFar) return t1;
    return -1.0;
}

void sphereIntersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const auto* s = static_cast<const Sphere*>(args->geometryUserPtr);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    const unsigned N = args->N;
    Vec3 o(RTCRayN_org_x(ray, N, 0), RTCRayN_org_y(ray, N, 0), RTCRayN_org_z(ray, N, 0));
    Vec3 d(RTCRayN_dir_x(ray, N, 0), RTCRayN_dir_y(ray, N, 0), RTCRayN_dir_z(ray, N, 0));
    double t = sphereRoot(*s, o, d, RTCRayN_tnear(ray, N, 0), RTCRayN_tfar(ray, N, 0));
    if (t < 0.0) return;
    Vec3 n = o + d * float(t) - s->center;
    RTCRayN_tfar(ray, N, 0) = float(t);
    RTCHitN_Ng_x(hit, N, 0) = n.x;
    RTCHitN_Ng_y(hit, N, 0) = n.y;
    RTCHitN_Ng_z(hit, N, 0) = n.z;
    RTCHitN_u(hit, N, 0) = 0.f;
    RTCHitN_v(hit, N, 0) = 0.f;
    RTCHitN_primID(hit, N, 0) = args->primID;
    RTCHitN_geomID(hit, N, 0) = args->geomID;
    RTCHitN_instID(hit, N, 0, 0) = args->context->instID[0];
}

void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const auto* s = static_cast<const Sphere*>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN* ray = args->ray;
    Vec3 o(RTCRayN_org_x(ray, N, 0), RTCRayN_org_y(ray, N, 0), RTCRayN_org_z(ray, N, 0));
    Vec3 d(RTCRayN_dir_x(ray, N, 0), RTCRayN_dir_y(ray, N, 0), RTCRayN_dir_z(ray, N, 0));
    if (sphereRoot(*s, o, d, RTCRayN_tnear(ray, N, 0), RTCRayN_tfar(ray, N, 0)) >= 0.0)
        RTCRayN_tfar(ray, N, 0) = -kInfinity;  // Embree's convention for "occluded"
}

ShapeInfo shapeInfo(ShapeType type, int material, int interiorMedium) {
    ShapeInfo info;
    info.type = type;
    info.material = material;
    info.interiorMedium = interiorMedium;
    return info;
}

}  // namespace

Ray spawnRay(const SurfaceHit& hit, const Vec3& dir, float tMax) {
    float eps = surfaceEpsilon(hit.p);
    Vec3 o = hit.p + hit.ng * (dot(dir, hit.ng) >= 0.f ? eps : -eps);
    return {o, dir, tMax};
}

GeometryScene::GeometryScene() : mEmbree(std::make_unique<Embree>()) {
    mEmbree->device = rtcNewDevice(nullptr);
    if (!mEmbree->device) throw MirageError("Embree: cannot create a device for the surfaces");
    rtcSetDeviceErrorFunction(mEmbree->device, onEmbreeError, &mEmbree->error);
    mEmbree->scene = rtcNewScene(mEmbree->device);
    // Robust traversal: watertight triangle tests, so that rays through a shared mesh edge
    // (the seam of a quad's two triangles) cannot slip between them.
    rtcSetSceneFlags(mEmbree->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(mEmbree->scene, RTC_BUILD_QUALITY_HIGH);
}

GeometryScene::~GeometryScene() = default;

int GeometryScene::addMaterial(Material m) {
    mMaterials.push_back(std::move(m));
    return int(mMaterials.size()) - 1;
}

int GeometryScene::addTriangles(TriangleData data, ShapeInfo info) {
    MIRAGE_CHECK(!mCommitted);
    MIRAGE_CHECK(info.material >= 0 && size_t(info.material) < mMaterials.size());
    RTCGeometry g = rtcNewGeometry(mEmbree->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t nv = data.positions.size(), nt = data.indices.size() / 3;
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), nt));
    if (!v || !idx) throw MirageError("Embree: " + mEmbree->error);
    for (size_t i = 0; i < nv; ++i) {
        v[3 * i] = data.positions[i].x;
        v[3 * i + 1] = data.positions[i].y;
        v[3 * i + 2] = data.positions[i].z;
        info.bounds.expand(data.positions[i]);
    }
    std::memcpy(idx, data.indices.data(), nt * 3 * sizeof(uint32_t));
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(mEmbree->scene, g);
    rtcReleaseGeometry(g);
    MIRAGE_CHECK(id == mShapes.size());
    info.triangles = nt;
    mBounds.expand(info.bounds);
    mShapes.push_back(info);
    mSpheres.emplace_back();
    mTriangles.push_back(std::make_unique<TriangleData>(std::move(data)));
    return int(id);
}

int GeometryScene::addMesh(const TriangleMesh& mesh, const Transform& xf, int material,
                           int interiorMedium) {
    TriangleData data;
    data.indices = mesh.indices;
    for (const Vec3& p : mesh.positions) data.positions.push_back(xf.point(p));
    if (!mesh.normals.empty()) {
        // Normals transform by the inverse transpose of the linear part.
        Mat3 inv = xf.linear.inverse();
        for (const Vec3& n : mesh.normals) {
            Vec3d nd(n);
            Vec3 w(Vec3d(inv(0, 0) * nd.x + inv(1, 0) * nd.y + inv(2, 0) * nd.z,
                          inv(0, 1) * nd.x + inv(1, 1) * nd.y + inv(2, 1) * nd.z,
                          inv(0, 2) * nd.x + inv(1, 2) * nd.y + inv(2, 2) * nd.z));
            data.normals.push_back(length(w) > 0.f ? normalize(w) : Vec3(0.f));
        }
    }
    ShapeInfo info = shapeInfo(ShapeType::Mesh, material, interiorMedium);
    return addTriangles(std::move(data), info);
}

int GeometryScene::addQuad(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV,
                           int material, int interiorMedium) {
    TriangleData data;
    data.positions = {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
    data.indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise about edgeU × edgeV
    ShapeInfo info = shapeInfo(ShapeType::Quad, material, interiorMedium);
    info.center = corner;
    info.edgeU = edgeU;
    info.edgeV = edgeV;
    return addTriangles(std::move(data), info);
}

int GeometryScene::addSphere(const Vec3& center, float radius, int material, int interiorMedium) {
    MIRAGE_CHECK(!mCommitted);
    MIRAGE_CHECK(material >= 0 && size_t(material) < mMaterials.size());
    auto sphere = std::make_unique<SphereData>(SphereData{center, radius});
    static_assert(sizeof(SphereData) == sizeof(Sphere), "the callbacks read SphereData as Sphere");
    RTCGeometry g = rtcNewGeometry(mEmbree->device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryUserData(g, sphere.get());
    rtcSetGeometryBoundsFunction(g, sphereBounds, nullptr);
    rtcSetGeometryIntersectFunction(g, sphereIntersect);
    rtcSetGeometryOccludedFunction(g, sphereOccluded);
    rtcCommitGeometry(g);
    unsigned id = rtcAttachGeometry(mEmbree->scene, g);
    rtcReleaseGeometry(g);
    MIRAGE_CHECK(id == mShapes.size());
    ShapeInfo info = shapeInfo(ShapeType::Sphere, material, interiorMedium);
    info.center = center;
    info.radius = radius;
    info.bounds.expand(center - Vec3(radius));
    info.bounds.expand(center + Vec3(radius));
    mBounds.expand(info.bounds);
    mShapes.push_back(info);
    mSpheres.push_back(std::move(sphere));
    mTriangles.emplace_back();
    return int(id);
}

std::shared_ptr<const Region> GeometryScene::interiorRegion(int shape) const {
    const ShapeInfo& info = mShapes[size_t(shape)];
    if (info.type == ShapeType::Sphere) return makeSphereRegion(info.center, info.radius);
    if (info.type == ShapeType::Quad) return nullptr;
    const TriangleData& t = *mTriangles[size_t(shape)];
    return makeMeshRegion(t.positions, t.indices);
}

void GeometryScene::commit() {
    const auto t0 = Clock::now();
    commitEmbreeScene(mEmbree->scene);
    mBuildSeconds = secondsSince(t0);
    mCommitted = true;
    if (!mEmbree->error.empty()) throw MirageError("surfaces: " + mEmbree->error);
}

std::optional<SurfaceHit> GeometryScene::intersect(const Ray& ray) const {
    if (mShapes.empty()) return std::nullopt;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    // Embree asserts on a ray it cannot trace (non-finite origin or direction): such a ray
    // meets nothing, and the non-finite path it belongs to is dropped by its caller.
    if (!(isFinite(ray.o) && isFinite(ray.d) && ray.tMax >= 0.f)) return std::nullopt;
    RTCRayHit rh = embreeRayHit(ray.o, ray.d, 0.f, ray.tMax);
    rtcIntersect1(mEmbree->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    SurfaceHit h;
    h.t = rh.ray.tfar;
    h.shape = int(rh.hit.geomID);
    const ShapeInfo& info = mShapes[size_t(h.shape)];
    h.material = info.material;
    if (info.type == ShapeType::Sphere) {
        const SphereData& s = *mSpheres[size_t(h.shape)];
        h.ng = normalize(ray.at(h.t) - s.center);
        // Re-project on the sphere: the position error then does not grow with t.
        h.p = s.center + h.ng * s.radius;
        h.ns = h.ng;
        return h;
    }
    const TriangleData& m = *mTriangles[size_t(h.shape)];
    const uint32_t* tri = &m.indices[3 * size_t(rh.hit.primID)];
    const Vec3 &p0 = m.positions[tri[0]], &p1 = m.positions[tri[1]], &p2 = m.positions[tri[2]];
    float u = rh.hit.u, v = rh.hit.v;
    // Barycentric position: more accurate than o + t d far from the origin.
    h.p = p0 * (1.f - u - v) + p1 * u + p2 * v;
    h.ng = normalize(cross(p1 - p0, p2 - p0));
    h.ns = h.ng;
    if (!m.normals.empty()) {
        Vec3 n = m.normals[tri[0]] * (1.f - u - v) + m.normals[tri[1]] * u + m.normals[tri[2]] * v;
        if (length(n) > 0.f) {
            n = normalize(n);
            h.ns = dot(n, h.ng) < 0.f ? -n : n;
        }
    }
    return h;
}

bool GeometryScene::occluded(const Vec3& p, const Vec3& dir, float tMax) const {
    if (mShapes.empty() || !(tMax > 0.f) || !(isFinite(p) && isFinite(dir))) return false;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay r;
    r.org_x = p.x;
    r.org_y = p.y;
    r.org_z = p.z;
    r.dir_x = dir.x;
    r.dir_y = dir.y;
    r.dir_z = dir.z;
    r.tnear = 0.f;
    r.tfar = tMax;
    r.mask = ~0u;
    r.flags = 0;
    r.time = 0.f;
    rtcOccluded1(mEmbree->scene, &ctx, &r);
    return r.tfar < 0.f;
}

}  // namespace mirage
