#include "medium/ocean_components.h"

#include <vector>

#include "spectrum/ocean_spectra.h"

namespace mirage {

void makeWater(MediumComponent* c) {
    c->kind = ComponentKind::Water;
    c->sigmaA = ocean::waterAbsorption();
    c->sigmaS = ocean::waterScatteringSpectrum();
    c->phase = PhaseKind::Water;
    c->g = 0.f;
}

void makeCdom(MediumComponent* c, float slopePerNm) {
    c->kind = ComponentKind::Cdom;
    c->sigmaA = ocean::cdomShapeSpectrum(slopePerNm);
    c->sigmaS = Spectrum(0.f);
}

void makeChlorophyll(MediumComponent* c, float g) {
    c->kind = ComponentKind::Chlorophyll;
    c->sigmaA = ocean::bricaudA();
    std::vector<float> exponent(Spectrum::kDenseSamples), bp(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        float l = kLambdaMin + float(i);
        exponent[i] = 1.f - ocean::bricaudB()(l);
        bp[i] = ocean::particleScatteringPerUnit(l);
    }
    c->sigmaAExponent = Spectrum::fromDense(std::move(exponent));
    c->sigmaS = Spectrum::fromDense(std::move(bp));
    c->sigmaSExponent = ocean::kParticleScatteringExponent;
    c->phase = PhaseKind::HenyeyGreenstein;
    c->g = g;
}

const char* componentKindName(ComponentKind kind) {
    switch (kind) {
        case ComponentKind::Linear: return "linear";
        case ComponentKind::Water: return "water";
        case ComponentKind::Cdom: return "cdom";
        case ComponentKind::Chlorophyll: return "chlorophyll";
    }
    return "?";
}

}  // namespace mirage
