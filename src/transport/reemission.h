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
// photon walk's power × λi/λo above.
//
// A source like emission, S enters the null-collision form of the transfer equation beside
// σs Ls and σn L; at a tentative collision (rate σ̄) a camera path estimates S/σ̄ by an event of
// its own, not as a branch of absorption: absorption is chosen in proportion to σa at the
// path's wavelengths, which can be 0 at λo where λi is absorbed (a dye that absorbs blue and
// glows red would never re-emit on a red path). A fluorescent component c is drawn uniformly
// (1/n_f) and chosen with probability
//   P_f = min(½, Γ_c max(P_a, σ̂a,c(x) / σ̄)),   σ̂a,c(x) = max of σa,c(x, λ) over 360, 420, …,
// 780 nm: positive wherever c absorbs at all, and never rarer than the branch of absorption it
// replaces (P_a, the path's probability of absorption, a symmetric function of its
// wavelengths), which keeps its weights as small as that branch's were. Chosen, λi is drawn uniformly
// over [360 nm, λmax] (q = 1/(λmax − 360); λmax the longest of the path's wavelengths, or
// 830 nm where anti-Stokes emission is allowed), the path goes on at λi along an isotropic wi
// (its density 1/4π cancels the isotropic emission's), and
//   β(λo) ← β(λo) · n_f Γ_c σa,c(x, λi) η_c(λi → λo) (λi/λo) / (q σ̄ P_f);
// not chosen, the ordinary events follow with their weights divided by 1 − P_f. Neither P_f,
// nor the choice, nor the density of λi singles out the hero wavelength (λmax is a symmetric
// function of the four), which is what lets the path keep only its hero wavelength after the
// event: hero wavelength sampling stays unbiased only if the choice to drop the others is
// symmetric in the path's wavelengths.
struct InelasticEvent {
    bool chosen = false;
    float otherScale = 1.f;  // not chosen: 1 / (1 − P_f), for the ordinary events' weights
    float lambdaInNm = 0;
    Vec3 wi;                 // chosen: direction to continue along (light arrived from −wi)
    float weight = 0;        // chosen: the factor on β(λo) above (0 when η(λi → λo) = 0)
};
// λo is w.lambda[0], the hero. Draws 5 numbers in a fluorescent medium and none in any other
// (then: not chosen, scale 1).
InelasticEvent sampleInelasticEvent(const Medium& m, Medium::Context& ctx, const Vec3& pWorld,
                                    const SampledWavelengths& w, float sigmaMaj, float pAbsorb,
                                    Sampler& sampler);

}  // namespace mirage
