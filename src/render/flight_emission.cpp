#include "render/flight_emission.h"

namespace mirage {

FlightEmission::FlightEmission(const EmissionLight& light, const Ray& ray, float tEnd,
                               Sampler& sampler, TrackingContext& tracking)
    : mRay(ray) {
    if (!light.sampleDistance(ray, tEnd, tracking, sampler.get1D(), false, &mPoint)) return;
    mLight = &light;
    mPending = true;
}

float FlightEmission::shareAt(const Collision& c, TrackingContext& tracking) const {
    const float p = mLight->distancePdf(mRay, c.t, mPoint.mass, false, tracking);
    // σ̄² / (σ̄² + p²) as a ratio: squares of majorants up to 1e30 (medium.h) overflow floats.
    const float r = p / c.sigmaMaj;
    return 1.f / (1.f + r * r);
}

void FlightEmission::score(const SampledSpectrum& beta, TrackingContext& tracking,
                           PathRecorder& rec) {
    mPending = false;
    for (size_t i = 0; i < tracking.size(); ++i) {
        const Medium& m = tracking.medium(i);
        if (!m.emissive() || rec.holdout(i)) continue;
        Medium::Context& ctx = tracking.context(i);
        const Vec3 p = ctx.toObject(mRay).at(mPoint.t);
        MediumPoint mp;
        m.eval(p, ctx, &mp);
        ++tracking.lookups;
        const SampledSpectrum emitted = mp.sigmaA * mp.Le;
        if (emitted.isZero()) continue;
        const float sigmaMaj =
            tracking.pathMajorant(i) >= 0.f ? tracking.pathMajorant(i) : m.majorant().at(p);
        // (1/p) p² / (σ̄² + p²), as collisionShare keeps it finite.
        const float r = sigmaMaj / mPoint.pdf;
        rec.emittedInMedium(beta * emitted * (1.f / (mPoint.pdf * (1.f + r * r))), mPoint.t,
                            mp.temperature);
    }
}

}  // namespace mirage
