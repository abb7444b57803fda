#include "render/achromatic_film.h"

#include <algorithm>
#include <cmath>

#include "spectrum/spectrum.h"
#include "spectrum/spectrum_sampling.h"

namespace mirage {

namespace {

// The visible range at the film's 1 nm resolution (spectrum/spectrum.h).
template <typename F>
void forEachDenseLambda(F&& f) {
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) f(kLambdaMin + float(i));
}

// Two spectra proportional to each other, each normalised by its maximum, to float rounding.
bool sameShape(const Spectrum& a, const Spectrum& b) {
    const float ma = a.maxValue(), mb = b.maxValue();
    bool same = ma > 0.f && mb > 0.f;
    forEachDenseLambda([&](float l) { same = same && std::abs(a(l) / ma - b(l) / mb) <= 1e-5f; });
    return same;
}

bool positiveEverywhere(const Spectrum& s) {
    bool positive = true;
    forEachDenseLambda([&](float l) { positive = positive && s(l) > 0.f; });
    return positive;
}

// The lights' common shape, or nothing (with the reason) when they have none.
std::optional<Spectrum> commonLightShape(const RenderScene& scene, std::string* why) {
    if (scene.lights.empty()) {
        *why = "no lights";
        return std::nullopt;
    }
    const Spectrum* first = scene.lights.front()->spectrum();
    for (const auto& light : scene.lights) {
        const Spectrum* s = light->spectrum();
        if (!s || !first || !sameShape(*s, *first)) {
            *why = "lights of different colours";
            return std::nullopt;
        }
    }
    if (!positiveEverywhere(*first)) {
        *why = "a light spectrum with zeros";
        return std::nullopt;
    }
    return *first;
}

// Empty when every medium is grey and nothing else is spectral; else what is.
std::string spectralPart(const RenderScene& scene) {
    if (scene.hasSurfaces()) return "surfaces";
    for (const auto& m : scene.media) {
        if (!m->greyCoefficients()) return "spectral or fluorescent media";
        if (m->emissive()) return "emission";
    }
    std::string why;
    if (!commonLightShape(scene, &why)) return why;
    return "";
}

}  // namespace

std::optional<AchromaticFilm> AchromaticFilm::forScene(const RenderScene& scene,
                                                       const Integrator& integrator) {
    if (!integrator.lightShapedRadiance() || !spectralPart(scene).empty()) return std::nullopt;
    std::string why;
    Spectrum shape = *commonLightShape(scene, &why);
    const Vec3d xyz = spectrumToXyz(shape);
    const Vec3d perWatt = xyz / SpectrumSampler(shape).integral();
    return AchromaticFilm(std::move(shape), Vec3(float(xyz.x), float(xyz.y), float(xyz.z)),
                          Vec3(float(perWatt.x), float(perWatt.y), float(perWatt.z)));
}

void AchromaticFilm::apply(const SampledWavelengths& w, RadianceSample* rs) const {
    const SampledSpectrum s = mShape.sample(w);
    float ls = 0.f, ss = 0.f;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        ls += rs->L[i] * s[i];
        ss += s[i] * s[i];
    }
    rs->xyz += mXyz * (ls / ss);
    rs->L = SampledSpectrum(0.f);
}

bool sampledColour(const RenderScene& scene, std::string* why) {
    const std::string part = spectralPart(scene);
    *why = part.empty()
               ? "grey media, one light colour: single and volpath add each sample's "
                 "exact XYZ, photons carry the light's XYZ (without a [refraction] field): "
                 "no colour noise"
               : "4 wavelengths per sample (" + part + ")";
    return !part.empty();
}

}  // namespace mirage
