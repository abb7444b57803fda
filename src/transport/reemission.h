// The second Russian roulette of Gutierrez et al. 2005 (inelastic scattering): once the albedo
// roulette has decided that a photon (or a one-wavelength path) is absorbed at a point, which
// component absorbed it, and whether that component re-emits it.
//
// The absorbing component is drawn ∝ its σa,c(x, λ): the absorption event of the mixture is the
// superposition of the components' independent absorption processes, so the probability that
// component c caused it is σa,c/σa. The component re-emits with probability Γ_c, its quantum
// yield (photons out per photon absorbed), isotropically (molecules lose the memory of the
// incident direction before they emit), at λo drawn from its emission band η_c renormalised
// over the allowed wavelengths (fluorescence.h). Overall P(re-emission) = Σ_c σa,c Γ_c / σa,
// the mean quantum yield of the mixture at x and λi.
//
// Power. Γ counts photons, so photon number is conserved by a re-emission of probability Γ;
// a photon of wavelength λ carries energy hc/λ, so a photon-mapping photon of power Φ (watts:
// photons per second × hc/λi) re-emitted at λo carries Φ λi/λo. For λo ≥ λi (Stokes) that is
// ≤ Φ: energy is never created; the difference heats the medium.
#pragma once

#include "core/rng.h"
#include "medium/medium.h"

namespace mirage {

struct Reemission {
    int component = -1;   // the fluorescent component that re-emitted
    float lambdaNm = 0;   // new wavelength
    Vec3 wo;              // new direction (isotropic)
    float powerScale = 1; // λi / λo: the photon's power after re-emission, per unit before
};

// The Γ roulette at world point pWorld, after an absorption of wavelength lambdaInNm in
// medium m (whose context is ctx). Returns true and fills *out when the photon is re-emitted.
// Draws no random number when the medium has no fluorescent component, so a shader with
// Γ = 0 everywhere walks exactly as one without fluorescence. Uses 5 numbers otherwise.
bool sampleReemission(const Medium& m, Medium::Context& ctx, const Vec3& pWorld,
                      float lambdaInNm, Sampler& sampler, Reemission* out);

// The same event seen from a camera path (adjoint transport), which carries the wavelength λo
// the light *leaves* with and must find the λi it was absorbed at. Γ_c η_c(λi → λo) counts
// photons (photons re-emitted per nm of λo per photon absorbed); radiance L counts energy, and
// a photon of λ carries hc/λ, so the energy redistribution function is Γ_c η_c (λi/λo)
// (Mobley 1994, "Light and Water" §5.13) and the inelastic source of the radiative
// transfer equation (Gutierrez et al. 2005, in energy units) is
//   S(x, ω, λo) = Σ_c Γ_c ∫ σa,c(x, λi) η_c(λi → λo) (λi/λo) (1/4π) ∫ L(x, ω', λi) dω' dλi,
// η_c a density in λo (1/nm; zero for λo < λi under the Stokes rule). It is the adjoint of the
// photon walk's power × λi/λo above. One sample: a fluorescent component c uniformly
// (probability 1/n_f), the Γ_c roulette, λi uniform over the allowed range [360 nm, λo]
// (density q = 1/(λo − 360)), ω' uniform (its density 1/4π cancels the isotropic emission's).
// The path then continues at λi along wi with the weight
//   n_f σa,c(x, λi) η_c(λi → λo) (λi/λo) / q  (1/m; Γ_c cancels against its roulette),
// which the caller divides by its probability density of having chosen this collision's event
// (σ̄ P for delta tracking). Returns false when the Γ roulette ends the path; true, possibly
// with weight 0 (no λi can feed λo), when it passes. That decision does not depend on λo, which
// is what lets the caller keep only its hero wavelength from then on: hero wavelength sampling
// stays unbiased only if the choice to drop the others is symmetric in the path's wavelengths.
struct InelasticAdjoint {
    float lambdaInNm = 0;
    Vec3 wi;           // direction to continue along (the light arrived from −wi)
    float weight = 0;  // 1/m, see above
};
bool sampleInelasticAdjoint(const Medium& m, Medium::Context& ctx, const Vec3& pWorld,
                            float lambdaOutNm, Sampler& sampler, InelasticAdjoint* out);

}  // namespace mirage
