#include "transport/scatter_point.h"

namespace mirage {

ScatterPointWalk chooseScatterPoint(TrackingContext& ctx, const Ray& worldRay, float tEnd,
                                    const SampledSpectrum& beta, Sampler& sampler,
                                    SampledSpectrum* L) {
    ScatterPointWalk walk;
    SampledSpectrum T(1.f);
    // One uniform serves the whole reservoir: candidate j is kept with probability w̄_j / W_j
    // (W_j the running sum), u then rescaled to the part of [0, 1) that made the decision, so
    // it stays uniform and independent of the decisions so far.
    double u = sampler.get1Dd(), total = 0.0;
    SampledSpectrum chosenW(0.f);
    float chosenMean = 0.f;
    walk.reachedEnd = trackCollisions(ctx, worldRay, tEnd, sampler, [&](const Collision& c) {
        const Medium& m = ctx.medium(size_t(c.medium));
        if (m.emissive()) *L += beta * T * c.mp.sigmaA * c.mp.Le / c.sigmaMaj;
        const SampledSpectrum w = T * c.mp.sigmaS / c.sigmaMaj;
        const float wMean = w.average();
        if (wMean > 0.f) {
            total += wMean;
            const double keep = wMean / total;
            if (u < keep) {
                walk.collision = c;
                chosenW = w;
                chosenMean = wMean;
                u /= keep;
            } else {
                u = (u - keep) / (1.0 - keep);
            }
        }
        T *= (SampledSpectrum(c.sigmaMaj) - c.mp.sigmaA - c.mp.sigmaS) / c.sigmaMaj;
        return russianRoulette(&T, sampler) ? Track::Continue : Track::Stop;
    });
    walk.T = walk.reachedEnd ? T : SampledSpectrum(0.f);
    if (chosenMean > 0.f) {
        walk.chosen = true;
        walk.weight = chosenW * float(total / chosenMean);
    }
    return walk;
}

}  // namespace mirage
