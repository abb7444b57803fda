#include "photon/beam_estimate.h"

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <string>

#include "core/error.h"
#include "geometry/embree_commit.h"
#include "geometry/embree_ray.h"

namespace mirage {

// The Embree objects: one device and one scene holding all photon discs as one point geometry.
// Embree reports errors through a device callback rather than return codes; the first message
// is kept and turned into an exception once the build is done.
struct BeamEstimator::Bvh {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string error;
    // Distance the query ray starts behind the camera (see beam_estimate.h): more than twice the
    // largest disc radius, so Embree's self-intersection test never rejects a disc in the span.
    float backOff = 0.f;

    ~Bvh() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

// One ScatteringProbe (grid accessors, per-medium contexts) per thread that estimates.
struct BeamEstimator::Probes {
    explicit Probes(const std::vector<const Medium*>& media) : perThread(media) {}
    tbb::enumerable_thread_specific<ScatteringProbe> perThread;
};

namespace {

void onEmbreeError(void* user, RTCError code, const char* message) {
    auto* bvh = static_cast<std::string*>(user);
    if (bvh->empty())
        *bvh = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

// The context handed to rtcIntersect1, extended with what the filter needs. Embree passes the
// RTCIntersectContext pointer through to the filter unchanged, so the filter can cast back
// (the pattern of Embree's own tutorials); `base` must stay the first member.
struct QueryContext {
    RTCIntersectContext base;
    const Photon* photons;
    const float* radii;
    Vec3 o, d;          // the caller's ray
    float tMin, tMax;   // its span
    std::vector<BeamHit>* hits;
};

// Records the hit and rejects it, so that traversal continues to the next disc. The distance
// and projection are recomputed from the caller's ray rather than read from Embree's hit, so
// that they do not depend on the backed-off origin.
void collectHit(const RTCFilterFunctionNArguments* args) {
    if (!args->valid[0]) return;
    args->valid[0] = 0;
    const auto* q = reinterpret_cast<const QueryContext*>(args->context);
    uint32_t slot = RTCHitN_primID(args->hit, args->N, 0);
    Vec3 v = q->photons[slot].p - q->o;
    float t = dot(v, q->d);
    if (t < q->tMin || t > q->tMax) return;
    Vec3 perp = v - q->d * t;
    float d2 = dot(perp, perp);
    float r = q->radii[slot];
    if (d2 <= r * r) q->hits->push_back({slot, t, d2});
}

}  // namespace

BeamEstimator::BeamEstimator(const VolumePhotons& photons, std::vector<float> radii,
                             BeamKernel kernel)
    : mPhotons(&photons),
      mRadii(std::move(radii)),
      mKernel(kernel),
      mBvh(std::make_unique<Bvh>()),
      mProbes(std::make_unique<Probes>(photons.media())) {
    MIRAGE_CHECK(mRadii.size() == photons.size());
    const size_t n = photons.size();
    if (n == 0) return;

    // Build the scene: one vertex (x, y, z, r) per photon, in slot order, so primID = slot.
    mBvh->device = rtcNewDevice(nullptr);
    if (!mBvh->device) throw MirageError("Embree: cannot create a device for the photon discs");
    rtcSetDeviceErrorFunction(mBvh->device, onEmbreeError, &mBvh->error);
    mBvh->scene = rtcNewScene(mBvh->device);
    RTCGeometry geom = rtcNewGeometry(mBvh->device, RTC_GEOMETRY_TYPE_DISC_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n));
    float rMax = 0.f;
    if (v) {
        for (size_t i = 0; i < n; ++i) {
            const Vec3& p = photons.map()[i].p;
            v[4 * i + 0] = p.x;
            v[4 * i + 1] = p.y;
            v[4 * i + 2] = p.z;
            v[4 * i + 3] = mRadii[i];
            rMax = std::max(rMax, mRadii[i]);
        }
    }
    rtcSetGeometryIntersectFilterFunction(geom, collectHit);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(mBvh->scene, geom);
    rtcReleaseGeometry(geom);
    commitEmbreeScene(mBvh->scene);
    if (!mBvh->error.empty()) throw MirageError(mBvh->error);
    mBvh->backOff = 4.f * rMax + 1e-3f;
}

BeamEstimator::~BeamEstimator() = default;

void BeamEstimator::query(const Ray& ray, float tMin, float tMax,
                          std::vector<BeamHit>* hits) const {
    hits->clear();
    if (!mBvh->scene || !(tMin <= tMax)) return;
    QueryContext q;
    rtcInitIntersectContext(&q.base);
    q.photons = mPhotons->map().photons().data();
    q.radii = mRadii.data();
    q.o = ray.o;
    q.d = ray.d;
    q.tMin = tMin;
    q.tMax = tMax;
    q.hits = hits;

    // The Embree ray starts backOff behind the caller's origin; its span is the caller's
    // shifted by backOff, widened by the largest radius' worth of rounding slack (the filter
    // applies the exact span).
    const float back = mBvh->backOff;
    RTCRayHit rh = embreeRayHit(ray.o - ray.d * back, ray.d,
                                std::max(0.f, back + tMin - 0.25f * back),
                                tMax < kInfinity ? back + tMax + 0.25f * back : kInfinity);
    rtcIntersect1(mBvh->scene, &q.base, &rh);

    // Slot order makes the sum below independent of the traversal order; a disc reported twice
    // (a primitive referenced from two leaves) counts once.
    std::sort(hits->begin(), hits->end(),
              [](const BeamHit& a, const BeamHit& b) { return a.slot < b.slot; });
    hits->erase(std::unique(hits->begin(), hits->end(),
                            [](const BeamHit& a, const BeamHit& b) { return a.slot == b.slot; }),
                hits->end());
}

Vec3 BeamEstimator::estimate(const Ray& ray, float tMax, const RayOpticalDepth& depth,
                             std::vector<BeamHit>* hits, const ViewWeight& view,
                             const PhotonGroups& groups) const {
    if (depth.empty()) return Vec3(0.f);
    // Not clipped to the span of `depth`: the σs ratio decides where a disc counts. One whose
    // photon projects where nothing scatters (outside every medium's box or region) adds
    // nothing; T is held at its end values beyond the span. Clipped where the ray turns
    // opaque: what lies beyond is seen through T < e^−30.
    query(ray, 0.f, std::min(tMax, depth.reach()), hits);
    ScatteringProbe& probe = mProbes->perThread.local();
    probe.setTimeOffset(depth.timeOffset());  // σs along the ray at the ray's time
    const Vec3 wo = -ray.d;
    Vec3 sum(0.f);
    for (const BeamHit& h : *hits) {
        const Photon& ph = mPhotons->map()[h.slot];
        const float atPhoton = mPhotons->sigmaS(h.slot);
        if (!(atPhoton > 0.f)) continue;
        const float here = probe.eventDensity(ray.at(h.t), ph);
        if (!(here > 0.f)) continue;
        const float ratio = cappedDensityRatio(here, atPhoton);
        float w = kernelValue(h.d2, mRadii[h.slot]) * depth.transmittance(h.t, ph.lambda) *
                  mPhotons->phase(h.slot, wo) * ratio * view(ph.lambda);
        const Vec3 term = mPhotons->fluxXyz(h.slot) * w;
        sum += term;
        groups.add(ph, term);
    }
    return sum;
}

}  // namespace mirage
