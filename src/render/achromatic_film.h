// Colour without chromatic noise where nothing in the scene is spectral.
//
// The film estimates a pixel's XYZ from each sample's four wavelengths (spectrum/cie.h):
// X̂ = ¼ Σ_i L(λ_i) x̄(λ_i) / p(λ_i). In a scene whose media are all grey (σa and σs the same at
// every wavelength, nothing emits or fluoresces), without surfaces, and whose lights all share
// one spectral shape S(λ) (any powers), a camera path's radiance is L(λ) = G S(λ): G is a
// function of the path's other numbers alone, since nothing the path meets depends on λ. The
// film's G·X̂[S] then carries the wavelengths' noise as colour noise on a grey image (9 % of
// volpath's relMSE on the race scene, docs/performance-history.md, "Where single scattering's time
// goes"). Replacing X̂[S] by its expectation over the wavelengths, XYZ[S] (spectrumToXyz, once per
// render), is a conditional expectation (Rao–Blackwell): the same mean, less variance, every pixel
// exactly the lights' chromaticity. G is read back from the sample as the least-squares ratio
// Σ L_i S_i / Σ S_i², exact when L = G S; S > 0 over the visible range is required, so that the
// ratio exists for every draw of the wavelengths.
//
// The photon mapper's photons each carry one wavelength λ drawn ∝ S (light/light.h), so a
// photon's flux XYZ, Φ cmf(λ)/∫ȳ, is colour noise on such a scene too. Nothing a photon meets
// depends on λ, so the same conditional expectation replaces it by Φ E[cmf(λ)]/∫ȳ =
// Φ XYZ[S]/∫S dλ (xyzPerWatt): the photon map is filmed in the lights' exact colour.
//
// Lights of several colours (a warm sun and a blue sky fill): with K distinct shapes S_k, a
// path's radiance is L(λ) = Σ_k G_k S_k(λ), G_k again free of λ (light k's lights' share).
// Each sample's four wavelengths then give four equations in the K unknowns G_k, exact when
// the four vectors S_k(λ_i) are independent (distinct shapes, K ≤ 3 here); the film adds
// Σ_k G_k XYZ[S_k], the same conditional expectation, each colour's part in that colour
// exactly. G is solved by least squares, Σ_i S_j,i S_k,i G_k = Σ_i L_i S_j,i (K = 1: the
// ratio above, unchanged). A draw of λ at which the shapes are not independent (not met with
// distinct shapes; the Gram matrix's pivot below 1e-9 of its diagonal) is filmed spectrally.
// Each photon carries its own light's XYZ per watt (xyzPerWatt(light)).
//
// Blackbody emission in grey media (fire in its smoke): an emission event adds β σa Le / σ̄ with
// Le = intensity · B(λ, T) and β, σa free of λ, so its radiance is a factor times B(·, T), of a
// shape that changes from event to event with T: no fixed set of shapes to solve for. An
// integrator that records each event with its temperature (IntegratorInfo::exactEmission:
// volpath) instead adds the factor times XYZ[B(·, T)] (spectrum/blackbody_xyz.h), the same
// conditional expectation per event, and the lights' part of L is filmed as above (none, for a
// fire lit by itself alone).
#pragma once

#include <optional>
#include <vector>

#include "render/integrator.h"

namespace mirage {

class AchromaticFilm {
public:
    // The film's shortcut for this scene and integrator, or nothing when the scene is not
    // achromatic (above) or the integrator's radiance may depend on λ by itself
    // (Integrator::lightShapedRadiance).
    static std::optional<AchromaticFilm> forScene(const RenderScene& scene,
                                                  const Integrator& integrator);

    // Moves the sample's spectral radiance into its XYZ: xyz += Σ_k G_k · XYZ[S_k], L = 0.
    void apply(const SampledWavelengths& w, RadianceSample* rs) const;

    // The lights' distinct colours (1 to 3).
    size_t colours() const { return mShapes.size(); }
    // The film's XYZ for one watt of light `light` (its index in the scene), its wavelength
    // drawn ∝ its shape S over the visible range: XYZ[S]/∫S dλ (1/nm), ∫ by the trapezoids the
    // lights sample λ with (spectrum/spectrum_sampling.h). A photon of power Φ adds Φ × this.
    Vec3 xyzPerWatt(size_t light) const { return mXyzPerWatt[light]; }
    const std::vector<Vec3>& xyzPerWattOfLights() const { return mXyzPerWatt; }
    // Whether the scene's media glow and the integrator records each emission event in its
    // exact colour (ThreadState::exactEmission, spectrum/blackbody_xyz.h).
    bool exactEmission() const { return mExactEmission; }

private:
    AchromaticFilm(std::vector<Spectrum> shapes, std::vector<Vec3> xyz,
                   std::vector<Vec3> xyzPerWatt, bool exactEmission)
        : mShapes(std::move(shapes)),
          mXyz(std::move(xyz)),
          mXyzPerWatt(std::move(xyzPerWatt)),
          mExactEmission(exactEmission) {}
    // L = G S for one shape, exactly as it always was filmed.
    void applyOne(const SampledWavelengths& w, RadianceSample* rs) const;
    std::vector<Spectrum> mShapes;  // the lights' distinct spectral shapes (any scale)
    std::vector<Vec3> mXyz;         // their XYZ, in the film's normalisation
    std::vector<Vec3> mXyzPerWatt;  // per light: its shape's XYZ / ∫ its shape dλ
    bool mExactEmission;
};

// Whether the scene's colour is sampled at each sample's wavelengths, and why (for `mirage
// info`): false when it is achromatic (above, one light colour or up to 3), and then single,
// volpath and the photon mapper film it exactly. A scene whose grey media glow is achromatic
// to `integrator` when it films emission exactly (IntegratorInfo::exactEmission).
bool sampledColour(const RenderScene& scene, const IntegratorInfo& integrator, std::string* why);

}  // namespace mirage
