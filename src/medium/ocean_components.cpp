#include "medium/ocean_components.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
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

float case1CdomAbsorption440(float chl) {
    const float aw = ocean::waterAbsorption()(440.f);
    const float ap = kCase1ParticleA440 * std::pow(chl, kCase1ParticleExponent);
    return kCase1CdomFraction * (aw + ap);
}

void applyCase1Cdom(ShaderDesc* shader) {
    auto& comps = shader->components;
    for (size_t i = 0; i < comps.size(); ++i) {
        if (comps[i].kind != ComponentKind::Cdom || comps[i].covariesWith.empty()) continue;
        const std::string chlName = comps[i].covariesWith;
        const auto chl = std::find_if(comps.begin(), comps.end(), [&](const MediumComponent& c) {
            return c.name == chlName && c.kind == ComponentKind::Chlorophyll;
        });
        if (chl == comps.end())
            throw MirageError(shader->source + ": shader '" + shader->name + "': cdom component '" +
                              comps[i].name + "' covaries with '" + chlName +
                              "', which is not a chlorophyll component of the shader");
        // The particle term: a power law of the chlorophyll's own concentration field.
        MediumComponent particle = comps[i];
        particle.name = comps[i].name + "_chl";
        particle.kind = ComponentKind::Chlorophyll;
        particle.grid = chl->grid;
        particle.concentration = chl->concentration;
        particle.sigmaA = comps[i].sigmaA.scaled(kCase1CdomFraction * kCase1ParticleA440);
        particle.sigmaAExponent = Spectrum(kCase1ParticleExponent);
        particle.sigmaS = Spectrum(0.f);
        particle.sigmaSExponent = 1.f;
        particle.covariesWith.clear();
        // The water term: constant.
        MediumComponent& water = comps[i];
        water.grid.clear();
        water.concentration = kCase1CdomFraction * ocean::waterAbsorption()(440.f);
        water.covariesWith.clear();
        comps.insert(comps.begin() + ptrdiff_t(i) + 1, std::move(particle));
        ++i;
    }
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
