#include "transport/path_vertex.h"

namespace mirage {

void scoreEmission(const Collision& c, const Medium& medium, const PathThroughput& path,
                   SampledSpectrum* L) {
    if (medium.emissive()) *L += path.beta * c.mp.sigmaA * c.mp.Le / c.sigmaMaj;
}

CollisionOutcome collisionEvent(const Collision& c, const Medium& medium, PathThroughput& path,
                                Sampler& sampler, SampledSpectrum* L) {
    scoreEmission(c, medium, path, L);
    return chooseEvent(c, path, sampler);
}

CollisionOutcome chooseEvent(const Collision& c, PathThroughput& path, Sampler& sampler) {
    const EventProbabilities e = eventProbabilities(c, path.beta);
    const float pReal = e.pAbsorb + e.pScatter;
    if (sampler.get1D() < pReal) {
        // Absorption as a weight: the real collision scatters what σs/σt of it scatters.
        path.beta *= c.mp.sigmaS / (c.sigmaMaj * pReal);
        return {path.alive() ? MediumEvent::Scattered : MediumEvent::Absorbed, e.pAbsorb};
    }
    path.beta *= e.sigmaN / (c.sigmaMaj * e.pNull);
    return {MediumEvent::Null, e.pAbsorb};
}

bool continueAtSurface(const Material& material, const SurfaceHit& hit, const SampledWavelengths& w,
                       TransportMode mode, Sampler& sampler, PathSegment* path,
                       BsdfSample* sample) {
    const Vec3 wo = -path->ray.d;
    const Frame frame(hit.ns);
    const float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
    BsdfSample bs;
    if (!material.sample(frame.toLocal(wo), uc, u1, u2, w, mode, &bs)) return false;
    const Vec3 wi = frame.toWorld(bs.wi);
    const bool crosses = (dot(wi, hit.ng) > 0.f) != (dot(wo, hit.ng) > 0.f);
    if (crosses != bs.transmitted) return false;
    PathThroughput& throughput = path->throughput;
    throughput.beta *= bs.weight;
    if (bs.dispersed && !throughput.heroOnly) throughput.keepHeroOnly();
    path->ray = spawnRay(hit, wi);
    if (sample) *sample = bs;
    return true;
}

Vec3 samplePhase(const Medium& m, const Collision& c, const Vec3& dir, Sampler& sampler,
                 PathThroughput* path, float* pdfOut) {
    SampledSpectrum weight;
    float pdf;
    const float uc = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
    const Vec3 wo = m.phaseSample(c.mp, dir, uc, u1, u2, &weight, &pdf);
    if (pdfOut) *pdfOut = pdf;
    path->beta *= weight;
    return wo;
}

}  // namespace mirage
