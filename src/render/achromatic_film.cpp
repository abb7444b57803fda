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

// Colours of lights beyond this are sampled: more unknowns per sample than its 4 wavelengths
// pin down with margin (render/achromatic_film.h).
constexpr size_t kMaxColours = 3;

// The lights' distinct shapes and each light's among them (kSeveralShapes: a light of several,
// an image dome, whose photons' colours vary and are not one light's XYZ).
constexpr size_t kSeveralShapes = ~size_t(0);
struct LightShapes {
    std::vector<Spectrum> shapes;
    std::vector<size_t> ofLight;
    bool severalOfOneLight() const {
        return std::find(ofLight.begin(), ofLight.end(), kSeveralShapes) != ofLight.end();
    }
};

bool emits(const RenderScene& scene) {
    for (const auto& m : scene.media)
        if (m->emissive()) return true;
    return false;
}

// The lights' shapes, or nothing (with the reason) when a light has none (its colour varies)
// or they are too many. A scene lit by its emission alone has none.
std::optional<LightShapes> lightShapes(const RenderScene& scene, std::string* why) {
    if (scene.lights.empty() && !emits(scene)) {
        *why = "no lights";
        return std::nullopt;
    }
    LightShapes out;
    for (const auto& light : scene.lights) {
        const std::vector<const Spectrum*> shapes = light->spectralShapes();
        if (shapes.empty()) {
            *why = "a light whose colour varies over directions or points";
            return std::nullopt;
        }
        size_t k = 0;
        for (const Spectrum* s : shapes) {
            if (!positiveEverywhere(*s)) {
                *why = "a light spectrum with zeros";
                return std::nullopt;
            }
            k = 0;
            while (k < out.shapes.size() && !sameShape(*s, out.shapes[k])) ++k;
            if (k == out.shapes.size()) out.shapes.push_back(*s);
        }
        out.ofLight.push_back(shapes.size() == 1 ? k : kSeveralShapes);
    }
    if (out.shapes.size() > kMaxColours) {
        *why = "lights of more than " + std::to_string(kMaxColours) + " colours";
        return std::nullopt;
    }
    return out;
}

// Empty when every medium is grey and nothing else is spectral; else what is. A grey medium's
// blackbody emission is not, where the integrator films it exactly (exactEmission).
std::string spectralPart(const RenderScene& scene, bool exactEmission) {
    if (scene.hasSurfaces()) return "surfaces";
    for (const auto& m : scene.media) {
        if (!m->greyCoefficients()) return "spectral or fluorescent media";
        if (m->emissive() && !exactEmission) return "emission";
    }
    std::string why;
    if (!lightShapes(scene, &why)) return why;
    return "";
}

}  // namespace

std::optional<AchromaticFilm> AchromaticFilm::forScene(const RenderScene& scene,
                                                       const Integrator& integrator) {
    const bool exactEmission = integrator.info().exactEmission;
    if (!integrator.lightShapedRadiance() || !spectralPart(scene, exactEmission).empty())
        return std::nullopt;
    std::string why;
    LightShapes ls = *lightShapes(scene, &why);
    // A photon carries its light's one XYZ per watt: an image dome's photons have none.
    if (integrator.info().photonPass && ls.severalOfOneLight()) return std::nullopt;
    std::vector<Vec3> xyz, shapePerWatt, perWatt;
    for (const Spectrum& shape : ls.shapes) {
        const Vec3d c = spectrumToXyz(shape);
        const Vec3d w = c / SpectrumSampler(shape).integral();
        xyz.push_back(Vec3(float(c.x), float(c.y), float(c.z)));
        shapePerWatt.push_back(Vec3(float(w.x), float(w.y), float(w.z)));
    }
    for (size_t shape : ls.ofLight)
        perWatt.push_back(shape == kSeveralShapes ? Vec3(0.f) : shapePerWatt[shape]);
    return AchromaticFilm(std::move(ls.shapes), std::move(xyz), std::move(perWatt),
                          exactEmission && emits(scene));
}

void AchromaticFilm::apply(const SampledWavelengths& w, RadianceSample* rs) const {
    const size_t K = mShapes.size();
    if (K == 0) return;  // lit by its emission alone, which the recorder filmed exactly
    if (K == 1) return applyOne(w, rs);
    // The normal equations A G = b of the least-squares fit L_i = Σ_k G_k S_k(λ_i), in double:
    // A_jk = Σ_i S_j,i S_k,i, b_j = Σ_i L_i S_j,i.
    double S[kMaxColours][kSpectrumSamples], A[kMaxColours][kMaxColours], b[kMaxColours];
    for (size_t k = 0; k < K; ++k) {
        const SampledSpectrum s = mShapes[k].sample(w);
        for (int i = 0; i < kSpectrumSamples; ++i) S[k][i] = double(s[i]);
    }
    double norm2[kMaxColours];  // A's diagonal before elimination: |S_k|²
    for (size_t j = 0; j < K; ++j) {
        b[j] = 0.0;
        for (int i = 0; i < kSpectrumSamples; ++i) b[j] += double(rs->L[i]) * S[j][i];
        for (size_t k = 0; k < K; ++k) {
            A[j][k] = 0.0;
            for (int i = 0; i < kSpectrumSamples; ++i) A[j][k] += S[j][i] * S[k][i];
        }
        norm2[j] = A[j][j];
    }
    // Gaussian elimination; A is symmetric positive definite when the shapes are independent
    // at these wavelengths, so no pivoting. Pivot p over |S_p|² is the squared sine of S_p's
    // angle to the span of the shapes before it: a vanishing one is filmed spectrally (L kept).
    for (size_t p = 0; p < K; ++p) {
        if (!(A[p][p] > 1e-9 * norm2[p])) return;
        for (size_t r = p + 1; r < K; ++r) {
            const double f = A[r][p] / A[p][p];
            for (size_t c = p; c < K; ++c) A[r][c] -= f * A[p][c];
            b[r] -= f * b[p];
        }
    }
    double G[kMaxColours];
    for (size_t p = K; p-- > 0;) {
        double v = b[p];
        for (size_t c = p + 1; c < K; ++c) v -= A[p][c] * G[c];
        G[p] = v / A[p][p];
    }
    Vec3d sum(0.0);
    for (size_t k = 0; k < K; ++k) sum += Vec3d(mXyz[k]) * G[k];
    rs->xyz += Vec3(float(sum.x), float(sum.y), float(sum.z));
    rs->L = SampledSpectrum(0.f);
}

void AchromaticFilm::applyOne(const SampledWavelengths& w, RadianceSample* rs) const {
    const SampledSpectrum s = mShapes[0].sample(w);
    float ls = 0.f, ss = 0.f;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        ls += rs->L[i] * s[i];
        ss += s[i] * s[i];
    }
    rs->xyz += mXyz[0] * (ls / ss);
    rs->L = SampledSpectrum(0.f);
}

bool sampledColour(const RenderScene& scene, const IntegratorInfo& integrator, std::string* why) {
    const std::string part = spectralPart(scene, integrator.exactEmission);
    if (!part.empty()) {
        *why = "4 wavelengths per sample (" + part + ")";
        return true;
    }
    const LightShapes shapes = *lightShapes(scene, why);
    const size_t colours = shapes.shapes.size();
    if (integrator.photonPass && shapes.severalOfOneLight()) {
        *why = "4 wavelengths per sample (an image dome's photons, each of its own colour)";
        return true;
    }
    if (emits(scene)) {
        *why = "grey media glowing by their temperature: " + integrator.name +
               " adds each emission event's exact XYZ (the blackbody's at its temperature)" +
               (colours == 0 ? std::string(", and no light: no colour noise")
                             : ", and the lights' exact colour: no colour noise");
        return false;
    }
    *why = colours == 1 ? "grey media, one light colour: single and volpath add each sample's "
                          "exact XYZ, photons carry the light's XYZ (without a [refraction] "
                          "field): no colour noise"
                        : "grey media, " + std::to_string(colours) +
                              " light colours: single and volpath split each sample's "
                              "radiance by colour at its 4 wavelengths and add each part's "
                              "exact XYZ, photons carry their light's XYZ (without a "
                              "[refraction] field): no colour noise";
    return false;
}

}  // namespace mirage
