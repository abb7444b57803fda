#include "transport/reemission.h"

#include <algorithm>
#include <array>

#include "core/sampling.h"

namespace mirage {

bool sampleReemission(const Medium& m, Medium::Context& ctx, const Vec3& pWorld,
                      float lambdaInNm, Sampler& sampler, Reemission* out) {
    if (!m.fluorescent()) return false;
    const auto& comps = m.shader().components;
    const int n = int(comps.size());
    std::array<float, kMaxComponents> sigmaA{};
    Vec3 pObject = m.toObject(Ray{pWorld, Vec3(0.f, 0.f, 1.f), 0.f}).o;
    m.sigmaAComponentsAt(pObject, ctx, lambdaInNm, sigmaA.data());

    float uComponent = sampler.get1D(), uGamma = sampler.get1D(), uLambda = sampler.get1D();
    float u1 = sampler.get1D(), u2 = sampler.get1D();

    // The absorbing component, ∝ σa,c (the last one with σa > 0 if rounding runs past).
    float total = 0.f;
    for (int i = 0; i < n; ++i) total += sigmaA[size_t(i)];
    if (!(total > 0.f)) return false;
    int chosen = -1;
    float acc = 0.f;
    for (int i = 0; i < n; ++i) {
        if (sigmaA[size_t(i)] <= 0.f) continue;
        chosen = i;
        acc += sigmaA[size_t(i)];
        if (uComponent * total < acc) break;
    }
    const MediumComponent& c = comps[size_t(chosen)];
    if (!c.fluorescent() || uGamma >= c.quantumEfficiency) return false;

    float lambdaOut;
    if (!m.fluorescence(chosen).sample(lambdaInNm, uLambda, &lambdaOut)) return false;
    out->component = chosen;
    out->lambdaNm = lambdaOut;
    out->wo = sampleUniformSphere(u1, u2);
    out->powerScale = lambdaInNm / lambdaOut;
    return true;
}

bool sampleInelasticAdjoint(const Medium& m, Medium::Context& ctx, const Vec3& pWorld,
                            float lambdaOutNm, Sampler& sampler, InelasticAdjoint* out) {
    if (!m.fluorescent()) return false;
    const auto& comps = m.shader().components;
    std::array<int, kMaxComponents> fluorescent{};
    int nf = 0;
    for (size_t i = 0; i < comps.size(); ++i)
        if (comps[i].fluorescent()) fluorescent[size_t(nf++)] = int(i);

    float uComponent = sampler.get1D(), uGamma = sampler.get1D(), uLambda = sampler.get1D();
    float u1 = sampler.get1D(), u2 = sampler.get1D();

    int c = fluorescent[size_t(std::min(int(uComponent * float(nf)), nf - 1))];
    if (uGamma >= comps[size_t(c)].quantumEfficiency) return false;
    // From here on the answer is true: the roulette's outcome does not depend on λo.
    out->wi = sampleUniformSphere(u1, u2);
    out->weight = 0.f;
    const FluorescenceEmission& band = m.fluorescence(c);
    const float hi = band.antiStokes() ? kLambdaMax : std::min(lambdaOutNm, kLambdaMax);
    const float range = hi - kLambdaMin;
    if (!(range > 0.f)) return true;
    const float lambdaIn = kLambdaMin + uLambda * range;
    out->lambdaInNm = lambdaIn;
    const float eta = band.pdf(lambdaIn, lambdaOutNm);
    if (!(eta > 0.f)) return true;

    std::array<float, kMaxComponents> sigmaA{};
    Vec3 pObject = m.toObject(Ray{pWorld, Vec3(0.f, 0.f, 1.f), 0.f}).o;
    m.sigmaAComponentsAt(pObject, ctx, lambdaIn, sigmaA.data());
    // λi/λo: η counts photons, the path carries energy (reemission.h).
    out->weight = float(nf) * sigmaA[size_t(c)] * eta * (lambdaIn / lambdaOutNm) * range;
    return true;
}

}  // namespace mirage
