// The one place where a camera path's light enters its sample. An integrator's loop says what
// happened in its estimator's words — emitted here, lit by this estimate at this vertex,
// scattered at a medium or surface vertex, passed a mirror, escaped to the dome, the camera
// ray's coverage was this — and the recorder decides the rest: the beauty, the light-path class
// (core/light_path.h: it keeps the path's history), the light group (film/aov.h: it reads the
// light estimates' split by group), the place along the camera ray of a deep sample
// (film/deep.h), and the holdout and alpha rules (docs/aovs.md). Without passes and deep output
// each contribution costs what `L += c` costs, and the beauty keeps its bits.
//
// Deep placement: a path's contributions lie along the camera ray at the distance of their event
// while the path has not scattered (past mirrors and glass the view goes on), then at its first
// scattering vertex, for everything it gathers after it; light gathered along the whole camera
// ray at once (the dome, a photon estimate along it) is placed by the pixel.
//
// Holdouts: a holdout object seen before the path scattered is nothing to the camera: black, and
// only what lies in front of it covers the pixel. Light that has scattered meets it as any
// object.
#pragma once

#include <limits>
#include <vector>

#include "core/light_path.h"
#include "film/aov.h"
#include "film/deep.h"
#include "geometry/geometry_scene.h"
#include "medium/medium.h"
#include "photon/photon_groups.h"
#include "render/integrator.h"
#include "transport/path_vertex.h"
#include "transport/scatter_point.h"

namespace mirage {

class PathRecorder {
public:
    // Records into *out the camera sample ThreadState describes: its passes (ts.aov), deep record
    // (ts.deep), the data passes' record of the camera ray (ts.cameraData), and the light
    // estimates' split by group (ts.lightSplit). An integrator that adds to a sample another one
    // began (the photon part after single scattering) records into it with a recorder of its own.
    PathRecorder(RadianceSample* out, ThreadState& ts)
        : mOut(out), mAov(ts.aov), mDeep(ts.deep), mCameraData(ts.cameraData), mTs(&ts) {}

    // A walk that branches off the path where it is now (volpath's lobe walks): it adds to the
    // same sample, with a history of its own from here on.
    PathRecorder branch() const { return *this; }

    // The vertices, as the path meets them at distance t along its current ray: a medium vertex
    // (scattering, fluorescent re-emission), a diffuse surface vertex, a mirror or glass.
    void scatteredInMedium(float t) { scattered(t, false); }
    void scatteredAtSurface(float t) { scattered(t, true); }
    void passedSpecular(float t) {
        if (mHistory.vertices == 0) mViewT += t;
        mHistory.specular();
        mOnCameraRay = false;
    }

    // Light emitted by a medium or a surface at distance t along the current ray, reaching the
    // camera as c. A medium's blackbody at `kelvin` (> 0), where the render films emission in
    // its exact colour (ThreadState::exactEmission), adds c's XYZ at every wavelength instead.
    void emittedInMedium(const SampledSpectrum& c, float t, float kelvin = 0.f) {
        if (kelvin > 0.f && mTs->exactEmission) return emittedBlackbody(c, t, kelvin);
        emitted(c, t, false);
    }
    void emittedAtSurface(const SampledSpectrum& c, float t) { emitted(c, t, true); }
    // Next-event estimation's light `lit` at a vertex at distance t, reaching the camera through
    // the throughput beta; its groups are the parts the estimate left in ts.lightSplit.
    void litInMedium(const SampledSpectrum& beta, const SampledSpectrum& lit, float t) {
        gathered(beta, lit, t, false);
    }
    void litAtSurface(const SampledSpectrum& beta, const SampledSpectrum& lit, float t) {
        gathered(beta, lit, t, true);
    }
    // The lights at infinity `lit` met by a path's continuation where it left the scene, for
    // the medium vertex before, which left them to it (render/direct_light.h: skyAtEscape):
    // counted as that vertex's next-event estimate is, its groups in ts.lightSplit.
    void litByEscape(const SampledSpectrum& beta, const SampledSpectrum& lit) {
        const SampledSpectrum c = beta * lit;
        mOut->L += c;
        if (mDeep) mDeep->radiance.push_back({mFirst, c, Vec3(0.f)});
        if (!mAov) return;
        mAov->addPath(c, mHistory.emitted());
        mAov->addGroups(beta, mTs->lightSplit);
    }
    // The lights at infinity seen by a ray that leaves the scene: light seen straight from its
    // source, as emission is (docs/aovs.md).
    void escaped(const SampledSpectrum& c) {
        add(c, mHistory.emitted(), kEmissionGroup, kUnplaced);
    }

    // A flight that scores emission at its every collision (transport/scatter_point.h): into
    // the beauty, or, with passes or deep output, apart per collision, which
    // recordFlightEmission() then tags and places. beta: the path's throughput.
    EmissionSink flightEmission(const SampledSpectrum& beta) {
        mTs->emitted.clear();
        if (mAov || mDeep) return EmissionSink{beta, nullptr, &mTs->emitted};
        return EmissionSink{beta, &mOut->L, nullptr};
    }
    void recordFlightEmission() {
        for (const EmissionAt& e : mTs->emitted) emittedInMedium(e.L, e.t);
    }

    // Photon estimates (XYZ, each photon at its own wavelength). photonGroups() hands an
    // estimate the split by light group its passes ask for (inactive without), to be made
    // before the estimate that is recorded next: the volume photons' radiance along the
    // current ray, or the caustic and global maps' at a diffuse surface at distance t.
    PhotonGroups photonGroups(const std::vector<int>& slotOfLight);
    void photonsInMedium(const Vec3& xyz);
    void photonsAtSurface(const Vec3& caustic, const Vec3& global, float t);

    // Whether what the path meets is a holdout to it: a holdout object, met before the path
    // scattered.
    bool holdout(size_t medium) const {
        return mHistory.vertices == 0 && medium < mTs->holdouts->size() && (*mTs->holdouts)[medium];
    }
    bool holdout(const GeometryScene& g, const SurfaceHit& hit) const {
        return mHistory.vertices == 0 && g.holdout(hit);
    }

    // The camera ray, until the path's first vertex. Its flight's tentative collisions are the
    // data passes' too (render/camera_ray_data.h; null when none asks, or past the camera ray),
    // and the flight says how it ended: at the ray's end, or stopped at the last collision.
    CameraRayData* cameraRayData() const { return mOnCameraRay ? mCameraData : nullptr; }
    void cameraFlightEnded(bool reachedEnd);
    // The camera ray's coverage, the pixel's alpha (said on any later ray, it is ignored): when
    // the flight reached the plate (nothing, or a holdout surface) what lies behind shows by its
    // transmittance, and holdout media take heldOutShare of the coverage. A flight that ended in
    // a real event of a holdout medium shows the plate there.
    void coverage(bool reachedPlate, float transmittance, float heldOutShare = 0.f);
    void stoppedInHoldout() {
        if (mOnCameraRay) mOut->alpha = 0.f;
    }

    // A nested estimate: the integrator the curved camera wraps, along one chord of a curved
    // camera ray (render/curved_camera.cpp). li() records its passes apart (ThreadState::
    // nestedAov) and hands nothing to the data passes (the chords are not the camera ray);
    // addNested() then adds it seen through T, the chords' transmittance before it (spectral
    // parts), and k (every radiance part).
    template <typename Li>
    RadianceSample nested(Li&& li);
    void addNested(const RadianceSample& s, const SampledSpectrum& T, float k);
    // The coverage of a camera ray seen through the transmittance T, in front of what covers
    // `beyond` of the pixel (the curved camera: its chords, then its last ray); all of it when T
    // let nothing through.
    void coverageThrough(const SampledSpectrum& T, float beyond);

    // The path's estimate from what it gathered (PathThroughput::estimate), for every part.
    void finish(const PathThroughput& path);

private:
    // Radiance gathered along the whole camera ray (a photon estimate): placed by the pixel.
    static constexpr DeepAt kUnplaced{std::numeric_limits<float>::quiet_NaN(), false};

    DeepAt at(float t, bool surface) const {
        return mHistory.vertices == 0 ? DeepAt{mViewT + t, surface} : mFirst;
    }
    void scattered(float t, bool surface) {
        if (mHistory.vertices == 0) mFirst = {mViewT + t, surface};
        mHistory.scatter(surface);
        mOnCameraRay = false;
    }
    void emitted(const SampledSpectrum& c, float t, bool surface) {
        mOut->L += c;
        if (mDeep) mDeep->radiance.push_back({at(t, surface), c, Vec3(0.f)});
        if (!mAov) return;
        mAov->addPath(c, mHistory.emitted());
        mAov->addGroup(c, kEmissionGroup);
    }
    void gathered(const SampledSpectrum& beta, const SampledSpectrum& lit, float t, bool surface) {
        const SampledSpectrum c = beta * lit;
        mOut->L += c;
        if (mDeep) mDeep->radiance.push_back({at(t, surface), c, Vec3(0.f)});
        if (!mAov) return;
        mAov->addPath(c, mHistory.gathered(surface));
        mAov->addGroups(beta, mTs->lightSplit);
    }
    void add(const SampledSpectrum& c, LightPath p, int group, DeepAt where) {
        mOut->L += c;
        if (mDeep) mDeep->radiance.push_back({where, c, Vec3(0.f)});
        if (!mAov) return;
        mAov->addPath(c, p);
        mAov->addGroup(c, group);
    }
    void addXyz(const Vec3& c, LightPath p, DeepAt where);
    void emittedBlackbody(const SampledSpectrum& c, float t, float kelvin);

    RadianceSample* mOut;
    AovSample* mAov;
    DeepSample* mDeep;
    CameraRayData* mCameraData;
    ThreadState* mTs;
    PathHistory mHistory;
    bool mOnCameraRay = true;   // no vertex yet
    float mViewT = 0.f;         // distance along the camera's view to the current ray's origin
    DeepAt mFirst{0.f, false};  // the first scattering vertex
    bool mNestedReady = false;  // nestedAov holds this sample's layout
};

template <typename Li>
RadianceSample PathRecorder::nested(Li&& li) {
    if (mAov) {
        if (!mNestedReady) mTs->nestedAov = *mAov;
        mNestedReady = true;
        mTs->nestedAov.reset();
        mTs->aov = &mTs->nestedAov;
    }
    mTs->cameraData = nullptr;
    RadianceSample s = li();
    mTs->aov = mAov;
    mTs->cameraData = mCameraData;
    return s;
}

}  // namespace mirage
