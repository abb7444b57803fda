#include "render/camera_ray_data.h"

#include <optional>

namespace mirage {

namespace {

// The visible medium whose box the ray enters first before tEnd, −1 for none.
int firstVisibleMedium(const RenderScene& scene, const Ray& ray, float tEnd) {
    int first = -1;
    float tFirst = tEnd;
    for (size_t i = 0; i < scene.media.size(); ++i) {
        float t0, t1;
        if (scene.holdout(i) ||
            !scene.media[i]->worldBounds().intersect(ray.o, ray.d, 0.f, tFirst, &t0, &t1))
            continue;
        first = int(i);
        tFirst = t0;
    }
    return first;
}

}  // namespace

CameraRayData::CameraRayData(const RenderScene& scene, const Ray& ray, const SampledWavelengths& w,
                             Sampler& sampler, ThreadState& ts, AovSample* aov, DeepSample* deep)
    : mScene(scene),
      mRay(ray),
      mW(w),
      mSampler(sampler),
      mTs(ts),
      mAov(aov),
      mDeep(deep),
      mCrypto(aov && !aov->volumeCoverage.empty()) {}

void CameraRayData::seen(const Collision& c) {
    if (!mAlive) return;
    mLastT = c.t;
    const bool visible = !mScene.holdout(size_t(c.medium));
    if (visible) mAlbedo += mT * c.mp.sigmaS / c.sigmaMaj;
    const float before = mT.average();
    mT *= (SampledSpectrum(c.sigmaMaj) - c.mp.sigmaA - c.mp.sigmaS) / c.sigmaMaj;
    const float left = mT.average();
    if (!(mDepth < kInfinity) && left <= 0.5f) mDepth = c.t;
    // The coverage this collision adds (before the roulette rescales T), to the deep samples
    // and to the medium's Cryptomatte coverage.
    if (mDeep && visible) mDeep->coverage.push_back({{c.t, false}, before - left});
    if (mCrypto && visible) mAov->volumeCoverage[size_t(c.medium)] += before - left;
    mAlive = russianRoulette(&mT, mSampler);
    if (mAlive) return;
    if (mDeep && visible) mDeep->coverage.push_back({{c.t, false}, left});
    if (mCrypto && visible) mAov->volumeCoverage[size_t(c.medium)] += left;
}

void CameraRayData::finish() {
    std::optional<SurfaceHit> hit;
    if (mScene.hasSurfaces()) hit = mScene.geometry->intersect(mRay);
    const float tEnd = hit ? hit->t : mRay.tMax;
    // The integrator may have changed the context's wavelengths (fluorescence, dispersion).
    const SampledWavelengths& now = mTs.tracking.wavelengths();
    if (now.lambda != mW.lambda || now.pdf != mW.pdf) mTs.tracking.setWavelengths(mW);
    bool reached = mAlive && mWalk == Walk::ToTheEnd;
    if (mAlive && mWalk != Walk::ToTheEnd) {
        const float t0 = mLastT;
        const Ray rest{mRay.at(t0), mRay.d, mRay.tMax - t0};
        reached = trackCollisions(mTs.tracking, rest, tEnd - t0, mSampler, [&](Collision c) {
            c.t += t0;
            seen(c);
            return mAlive ? Track::Continue : Track::Stop;
        });
    }
    if (mCrypto) mAov->firstVolume = firstVisibleMedium(mScene, mRay, tEnd);
    if (!reached) mT = SampledSpectrum(0.f);
    if (hit && reached && mScene.geometry->holdout(*hit)) {
        // A holdout: no albedo and no coverage of its own; the plate behind it shows by T.
        if (!(mDepth < kInfinity)) mDepth = hit->t;
    } else if (hit && reached) {
        const Material& mat = mScene.geometry->materialAt(*hit);
        for (int i = 0; i < kSpectrumSamples; ++i) mAlbedo[i] += mT[i] * mat.albedo(mW.lambda[i]);
        if (!(mDepth < kInfinity)) mDepth = hit->t;
        if (mDeep) mDeep->coverage.push_back({{hit->t, true}, mT.average()});
        if (mCrypto) mAov->shapeCoverage[size_t(hit->shape)] += mT.average();
        mT = SampledSpectrum(0.f);
    }
    if (!mAov) return;
    mAov->depth = mDepth;
    mAov->albedo = mAlbedo;
    mAov->transmittance = mT;
}

}  // namespace mirage
