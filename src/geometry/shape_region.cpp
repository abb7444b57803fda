#include "geometry/shape_region.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "geometry/embree_commit.h"
#include "geometry/embree_ray.h"

namespace mirage {

namespace {

class SphereRegion : public Region {
public:
    SphereRegion(const Vec3& c, float r) : mCenter(c), mRadius(r) {}

    bool contains(const Vec3& p) const override {
        Vec3 v = p - mCenter;
        return dot(v, v) < mRadius * mRadius;
    }

    // Chord of |o + t d − c|² = r², in double (as GeometryScene's sphere intersection), so a
    // small sphere far from the ray origin keeps its near root.
    bool clip(const Ray& ray, float* t0, float* t1) const override {
        Vec3d oc = Vec3d(ray.o) - Vec3d(mCenter), d(ray.d);
        double a = dot(d, d), b = dot(oc, d), c = dot(oc, oc) - double(mRadius) * mRadius;
        double disc = b * b - a * c;
        if (!(disc > 0.0)) return false;
        double sq = std::sqrt(disc);
        double q = b > 0.0 ? -(b + sq) : -(b - sq);
        double r0 = q / a, r1 = q != 0.0 ? c / q : r0;
        if (r0 > r1) std::swap(r0, r1);
        *t0 = std::max(*t0, float(r0));
        *t1 = std::min(*t1, float(r1));
        return *t0 < *t1;
    }

    bool convex() const override { return true; }

    Bounds3 bounds() const override {
        Bounds3 b;
        b.expand(mCenter - Vec3(mRadius));
        b.expand(mCenter + Vec3(mRadius));
        return b;
    }

private:
    Vec3 mCenter;
    float mRadius;
};

void onEmbreeError(void* user, RTCError code, const char* message) {
    auto* error = static_cast<std::string*>(user);
    if (error->empty())
        *error = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

// Every crossing of the query ray, collected by an intersect filter that rejects each hit so
// that traversal goes on (the pattern of photon/beam_estimate.cpp); `base` must stay first.
struct CrossingContext {
    RTCIntersectContext base;
    std::vector<std::pair<uint32_t, float>>* hits;  // (triangle, t)
};

void collectCrossing(const RTCFilterFunctionNArguments* args) {
    if (!args->valid[0]) return;
    args->valid[0] = 0;
    const auto* q = reinterpret_cast<const CrossingContext*>(args->context);
    q->hits->push_back({RTCHitN_primID(args->hit, args->N, 0), RTCRayN_tfar(args->ray, args->N, 0)});
}

class MeshRegion : public Region {
public:
    MeshRegion(std::vector<Vec3> positions, std::vector<uint32_t> indices) {
        for (const Vec3& p : positions) mBounds.expand(p);
        mDevice = rtcNewDevice(nullptr);
        if (!mDevice) throw MirageError("Embree: cannot create a device for a mesh interior");
        rtcSetDeviceErrorFunction(mDevice, onEmbreeError, &mError);
        mScene = rtcNewScene(mDevice);
        RTCGeometry g = rtcNewGeometry(mDevice, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), positions.size()));
        auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
            indices.size() / 3));
        if (v && idx) {
            for (size_t i = 0; i < positions.size(); ++i) {
                v[3 * i] = positions[i].x;
                v[3 * i + 1] = positions[i].y;
                v[3 * i + 2] = positions[i].z;
            }
            std::copy(indices.begin(), indices.end(), idx);
        }
        rtcSetGeometryIntersectFilterFunction(g, collectCrossing);
        rtcCommitGeometry(g);
        rtcAttachGeometry(mScene, g);
        rtcReleaseGeometry(g);
        commitEmbreeScene(mScene);
        if (!mError.empty()) throw MirageError("mesh interior: " + mError);
    }
    ~MeshRegion() override {
        if (mScene) rtcReleaseScene(mScene);
        if (mDevice) rtcReleaseDevice(mDevice);
    }

    // Odd number of crossings along a fixed direction that no axis-aligned mesh edge or face
    // contains (so grazing hits are as unlikely as for any direction).
    bool contains(const Vec3& p) const override {
        if (!mBounds.contains(p)) return false;
        const Vec3 d = normalize(Vec3(0.5727f, 0.6101f, 0.5474f));
        std::vector<std::pair<uint32_t, float>> hits;
        crossings(Ray{p, d}, 0.f, kInfinity, &hits);
        return hits.size() % 2 == 1;
    }

    bool clip(const Ray& ray, float* t0, float* t1) const override {
        std::vector<std::pair<uint32_t, float>> hits;
        crossings(ray, *t0, *t1, &hits);
        float a = contains(ray.at(*t0)) ? *t0 : kInfinity;
        float b = contains(ray.at(*t1)) ? *t1 : -kInfinity;
        for (const auto& h : hits) {
            a = std::min(a, h.second);
            b = std::max(b, h.second);
        }
        if (!(a < b)) return false;
        *t0 = a;
        *t1 = b;
        return true;
    }

    bool convex() const override { return false; }
    Bounds3 bounds() const override { return mBounds; }

private:
    // Crossings in (tMin, tMax), each triangle once (a triangle may sit in two BVH leaves).
    void crossings(const Ray& ray, float tMin, float tMax,
                   std::vector<std::pair<uint32_t, float>>* hits) const {
        CrossingContext q;
        rtcInitIntersectContext(&q.base);
        q.hits = hits;
        RTCRayHit rh = embreeRayHit(ray.o, ray.d, tMin, tMax);
        rtcIntersect1(mScene, &q.base, &rh);
        std::sort(hits->begin(), hits->end());
        hits->erase(std::unique(hits->begin(), hits->end(),
                                [](const auto& x, const auto& y) { return x.first == y.first; }),
                    hits->end());
    }

    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
    std::string mError;
    Bounds3 mBounds;
};

}  // namespace

std::shared_ptr<const Region> makeSphereRegion(const Vec3& center, float radius) {
    return std::make_shared<SphereRegion>(center, radius);
}

std::shared_ptr<const Region> makeMeshRegion(std::vector<Vec3> positions,
                                             std::vector<uint32_t> indices) {
    return std::make_shared<MeshRegion>(std::move(positions), std::move(indices));
}

}  // namespace mirage
