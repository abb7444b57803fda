#include "transport/scatter_point.h"

namespace mirage {

ScatterPointWalk chooseScatterPoints(TrackingContext& ctx, const Ray& worldRay, float tEnd,
                                     Sampler& sampler, const EmissionSink& emission,
                                     CollisionObserver* observer, const ScatterGuide* guide,
                                     const std::vector<bool>* holdouts) {
    const SampledSpectrum& beta = emission.beta;
    ScatterPointWalk walk;
    SampledSpectrum T(1.f);
    // One uniform per reservoir, stratified: (u + k) / kScatterPoints. A reservoir fed with one
    // uniform keeps candidate j with probability w̄_j / W_j (W_j the running sum) and rescales u
    // to the part of [0, 1) that made the decision; the candidate it ends with is the inverse
    // of the weights' CDF (taken from the last candidate back) at u. Stratified uniforms thus
    // give systematic resampling: points spread along the ray ∝ T σs.
    const double u0 = sampler.get1Dd();
    double u[kScatterPoints], total = 0.0;
    SampledSpectrum chosenW[kScatterPoints];
    float chosenMean[kScatterPoints] = {};
    for (int k = 0; k < kScatterPoints; ++k) u[k] = (u0 + k) / kScatterPoints;
    walk.reachedEnd = trackCollisions(ctx, worldRay, tEnd, sampler, [&](const Collision& c) {
        if (observer) observer->seen(c);
        const Medium& m = ctx.medium(size_t(c.medium));
        const size_t mi = size_t(c.medium);
        const bool holdout = holdouts && mi < holdouts->size() && (*holdouts)[mi];
        if (holdout)
            walk.holdoutCoverage += (T * (c.mp.sigmaA + c.mp.sigmaS) / c.sigmaMaj).average();
        else if (m.emissive() && emission.parts)
            emission.parts->push_back({c.t, beta * T * c.mp.sigmaA * c.mp.Le / c.sigmaMaj});
        else if (m.emissive())
            *emission.L += beta * T * c.mp.sigmaA * c.mp.Le / c.sigmaMaj;
        const SampledSpectrum w = holdout ? SampledSpectrum(0.f) : T * c.mp.sigmaS / c.sigmaMaj;
        // The resampling weight: w̄, times the guide's guess of the light at the point.
        const float wMean = guide && w.average() > 0.f ? w.average() * guide->at(c.p) : w.average();
        if (wMean > 0.f) {
            total += wMean;
            const double keep = wMean / total;
            for (int k = 0; k < kScatterPoints; ++k) {
                if (u[k] < keep) {
                    walk.collision[k] = c;
                    chosenW[k] = w;
                    chosenMean[k] = wMean;
                    u[k] /= keep;
                } else {
                    u[k] = (u[k] - keep) / (1.0 - keep);
                }
            }
        }
        T *= (SampledSpectrum(c.sigmaMaj) - c.mp.sigmaA - c.mp.sigmaS) / c.sigmaMaj;
        return russianRoulette(&T, sampler) ? Track::Continue : Track::Stop;
    });
    walk.T = walk.reachedEnd ? T : SampledSpectrum(0.f);
    if (chosenMean[0] > 0.f) {
        walk.chosen = true;
        for (int k = 0; k < kScatterPoints; ++k)
            walk.weight[k] = chosenW[k] * float(total / (chosenMean[k] * kScatterPoints));
    }
    return walk;
}

}  // namespace mirage
