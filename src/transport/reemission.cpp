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
    Vec3 pObject = ctx.pointToObject(pWorld);
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

InelasticEvent sampleInelasticEvent(const Medium& m, Medium::Context& ctx, const Vec3& pWorld,
                                    const SampledWavelengths& w, float sigmaMaj, float pAbsorb,
                                    Sampler& sampler) {
    InelasticEvent out;
    if (!m.fluorescent()) return out;
    const auto& comps = m.shader().components;
    std::array<int, kMaxComponents> fluorescent{};
    int nf = 0;
    for (size_t i = 0; i < comps.size(); ++i)
        if (comps[i].fluorescent()) fluorescent[size_t(nf++)] = int(i);

    const float uComponent = sampler.get1D(), uChoose = sampler.get1D(), uLambda = sampler.get1D();
    const float u1 = sampler.get1D(), u2 = sampler.get1D();
    const size_t c = size_t(fluorescent[size_t(std::min(int(uComponent * float(nf)), nf - 1))]);
    const Vec3 pObject = ctx.pointToObject(pWorld);
    std::array<float, kMaxComponents> sigmaA{};
    float sigmaHat = 0.f;
    for (float lambda = 360.f; lambda <= 780.f; lambda += 60.f) {
        m.sigmaAComponentsAt(pObject, ctx, lambda, sigmaA.data());
        sigmaHat = std::max(sigmaHat, sigmaA[c]);
    }
    const float gamma = comps[c].quantumEfficiency;
    const float pf = std::min(0.5f, gamma * std::max(pAbsorb, sigmaHat / sigmaMaj));
    if (!(pf > 0.f)) return out;
    if (uChoose >= pf) {
        out.otherScale = 1.f / (1.f - pf);
        return out;
    }
    out.chosen = true;
    out.wi = sampleUniformSphere(u1, u2);
    const FluorescenceEmission& band = m.fluorescence(int(c));
    float hi = kLambdaMax;
    if (!band.antiStokes()) hi = std::min(kLambdaMax, *std::max_element(w.lambda.begin(), w.lambda.end()));
    const float range = hi - kLambdaMin;
    if (!(range > 0.f)) return out;
    const float lambdaIn = kLambdaMin + uLambda * range;
    out.lambdaInNm = lambdaIn;
    const float lambdaOut = w.lambda[0];
    const float eta = band.pdf(lambdaIn, lambdaOut);  // 0 below λi under the Stokes rule
    if (!(eta > 0.f)) return out;
    m.sigmaAComponentsAt(pObject, ctx, lambdaIn, sigmaA.data());
    // λi/λo: η counts photons, the path carries energy; q = 1/range.
    out.weight = float(nf) * gamma * sigmaA[c] * eta * (lambdaIn / lambdaOut) * range /
                 (sigmaMaj * pf);
    return out;
}

}  // namespace mirage
