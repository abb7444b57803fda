// The recorder's rules away from the innermost loops (path_recorder.h says what and why).
#include "render/path_recorder.h"

#include <algorithm>

#include "render/camera_ray_data.h"
#include "spectrum/blackbody_xyz.h"

namespace mirage {

PhotonGroups PathRecorder::photonGroups(const std::vector<int>& slotOfLight) {
    if (!mAov || mAov->groupXyz.empty()) return PhotonGroups();
    mTs->lightSplitXyz.assign(mAov->groupXyz.size(), Vec3(0.f));
    return PhotonGroups(&slotOfLight, &mTs->lightSplitXyz);
}

// The photons' radiance on the camera ray's side of a vertex: light that scattered before it
// scattered there (the photon pass stores no first interaction that a shadow ray computes).
void PathRecorder::photonsInMedium(const Vec3& xyz) {
    addXyz(xyz, LightPath::VolumeIndirect, kUnplaced);
}

void PathRecorder::photonsAtSurface(const Vec3& caustic, const Vec3& global, float t) {
    const Vec3 c = caustic + global;
    mOut->xyz += c;
    if (mDeep) mDeep->radiance.push_back({at(t, true), SampledSpectrum(0.f), c});
    if (!mAov) return;
    mAov->addPathXyz(caustic, LightPath::Caustic);
    mAov->addPathXyz(global, LightPath::SurfaceIndirect);
    if (!mAov->groupXyz.empty()) mAov->addGroupXyz(mTs->lightSplitXyz);
}

void PathRecorder::addXyz(const Vec3& c, LightPath p, DeepAt where) {
    mOut->xyz += c;
    if (mDeep) mDeep->radiance.push_back({where, SampledSpectrum(0.f), c});
    if (!mAov) return;
    mAov->addPathXyz(c, p);
    if (!mAov->groupXyz.empty()) mAov->addGroupXyz(mTs->lightSplitXyz);
}

// c = k B(λ_i, T) at the sample's wavelengths, k free of λ (a grey medium's emission event,
// render/achromatic_film.h): k by least squares over the four, exact up to rounding, then
// k XYZ[B(·, T)]. Where B vanishes at all four (far below the visible range's glow), so does c.
void PathRecorder::emittedBlackbody(const SampledSpectrum& c, float t, float kelvin) {
    const SampledWavelengths& w = mTs->tracking.wavelengths();
    double cb = 0.0, bb = 0.0;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        const double b = planck(w.lambda[i], kelvin) * 1e-9;
        cb += double(c[i]) * b;
        bb += b * b;
    }
    if (!(bb > 0.0)) return;
    const Vec3 xyz = blackbodyXyz(kelvin) * float(cb / bb);
    mOut->xyz += xyz;
    if (mDeep) mDeep->radiance.push_back({at(t, false), SampledSpectrum(0.f), xyz});
    if (!mAov) return;
    mAov->addPathXyz(xyz, mHistory.emitted());
    if (mAov->groupXyz.empty()) return;
    mAov->groupXyz[kEmissionGroup] += xyz;
    mAov->groupsLit = true;
}

void PathRecorder::cameraFlightEnded(bool reachedEnd) {
    if (CameraRayData* data = cameraRayData()) data->walked(reachedEnd);
}

void PathRecorder::coverage(bool reachedPlate, float transmittance, float heldOutShare) {
    if (!mOnCameraRay) return;
    mOut->alpha = clamp((reachedPlate ? 1.f - transmittance : 1.f) - heldOutShare, 0.f, 1.f);
}

void PathRecorder::addNested(const RadianceSample& s, const SampledSpectrum& T, float k) {
    mOut->L += s.L * T * k;
    mOut->xyz += s.xyz * k;
    if (mAov) mAov->addWeighted(mTs->nestedAov, T, k);
}

void PathRecorder::coverageThrough(const SampledSpectrum& T, float beyond) {
    mOut->alpha = T.maxValue() <= 0.f ? 1.f : 1.f - T.average() * (1.f - beyond);
}

void PathRecorder::finish(const PathThroughput& path) {
    mOut->L = path.estimate(mOut->L);
    if (mAov) mAov->forEachRadiance([&](SampledSpectrum& s) { s = path.estimate(s); });
    if (mDeep)
        for (DeepSample::Radiance& r : mDeep->radiance) r.L = path.estimate(r.L);
}

}  // namespace mirage
