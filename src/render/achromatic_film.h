// Colour without chromatic noise where nothing in the scene is spectral.
//
// The film estimates a pixel's XYZ from each sample's four wavelengths (spectrum/cie.h):
// X̂ = ¼ Σ_i L(λ_i) x̄(λ_i) / p(λ_i). In a scene whose media are all grey (σa and σs the same at
// every wavelength, nothing emits or fluoresces), without surfaces, and whose lights all share
// one spectral shape S(λ) (any powers), a camera path's radiance is L(λ) = G S(λ): G is a
// function of the path's other numbers alone, since nothing the path meets depends on λ. The
// film's G·X̂[S] then carries the wavelengths' noise as colour noise on a grey image (9 % of
// volpath's relMSE on the race scene, docs/performance.md). Replacing X̂[S] by its
// expectation over the wavelengths, XYZ[S] (spectrumToXyz, once per render), is a conditional
// expectation (Rao–Blackwell): the same mean, less variance, every pixel exactly the lights'
// chromaticity. G is read back from the sample as the least-squares ratio Σ L_i S_i / Σ S_i²,
// exact when L = G S; S > 0 over the visible range is required, so that the ratio exists for
// every draw of the wavelengths.
//
// The photon mapper's photons each carry one wavelength λ drawn ∝ S (light/light.h), so a
// photon's flux XYZ, Φ cmf(λ)/∫ȳ, is colour noise on such a scene too. Nothing a photon meets
// depends on λ, so the same conditional expectation replaces it by Φ E[cmf(λ)]/∫ȳ =
// Φ XYZ[S]/∫S dλ (xyzPerWatt): the photon map is filmed in the lights' exact colour.
#pragma once

#include <optional>

#include "render/integrator.h"

namespace mirage {

class AchromaticFilm {
public:
    // The film's shortcut for this scene and integrator, or nothing when the scene is not
    // achromatic (above) or the integrator's radiance may depend on λ by itself
    // (Integrator::lightShapedRadiance).
    static std::optional<AchromaticFilm> forScene(const RenderScene& scene,
                                                  const Integrator& integrator);

    // Moves the sample's spectral radiance into its XYZ: xyz += G · XYZ[S], L = 0.
    void apply(const SampledWavelengths& w, RadianceSample* rs) const;

    const Spectrum& shape() const { return mShape; }
    Vec3 xyz() const { return mXyz; }
    // The film's XYZ for one watt of the lights' light, its wavelength drawn ∝ S over the
    // visible range: XYZ[S]/∫S dλ (1/nm), ∫ by the trapezoids the lights sample λ with
    // (spectrum/spectrum_sampling.h). A photon of power Φ adds Φ × this (above).
    Vec3 xyzPerWatt() const { return mXyzPerWatt; }

private:
    AchromaticFilm(Spectrum shape, Vec3 xyz, Vec3 xyzPerWatt)
        : mShape(std::move(shape)), mXyz(xyz), mXyzPerWatt(xyzPerWatt) {}
    Spectrum mShape;   // the lights' common spectral shape (any scale)
    Vec3 mXyz;         // its XYZ, in the film's normalisation
    Vec3 mXyzPerWatt;  // mXyz / ∫ mShape dλ
};

// Whether the scene's colour is sampled at each sample's wavelengths, and why (for `mirage
// info`): false when it is achromatic (above), and then single, volpath and the photon mapper
// film it exactly.
bool sampledColour(const RenderScene& scene, std::string* why);

}  // namespace mirage
