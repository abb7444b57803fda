#include "medium/rayleigh_particles.h"

#include <cmath>
#include <vector>

namespace mirage {

double rayleighCrossSection(double diameterM, double index, double lambdaM) {
    const double pi5 = std::pow(M_PI, 5);
    const double d3 = diameterM * diameterM * diameterM, l2 = lambdaM * lambdaM;
    const double lorentz = (index * index - 1.0) / (index * index + 2.0);
    return (2.0 * pi5 / 3.0) * (d3 * d3) / (l2 * l2) * lorentz * lorentz;
}

void makeRayleighParticles(MediumComponent* c, double diameterNm, double index,
                           double numberDensity) {
    std::vector<float> sigmaS(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i)
        sigmaS[size_t(i)] = float(numberDensity * rayleighCrossSection(diameterNm * 1e-9, index,
                                                                       (kLambdaMin + i) * 1e-9));
    c->kind = ComponentKind::Linear;
    c->sigmaA = Spectrum(0.f);
    c->sigmaS = Spectrum::fromDense(std::move(sigmaS));
    c->phase = PhaseKind::Rayleigh;
    c->g = 0.f;
}

}  // namespace mirage
