// The sea-water component kinds (shader.h) as spectra: what `kind = "water" | "cdom" |
// "chlorophyll"` in a shader file means, in one place for the loader, the tests and the slab
// instrument. Each sets the component's kind, σ spectra, exponents and phase lobe; the caller
// keeps its name, grid and concentration (and, for fluorescence, Γ and the band).
#pragma once

#include "medium/shader.h"

namespace mirage {

// HG asymmetry of marine particles: Petzold's average particle phase function has a mean
// cosine of 0.924 (Mobley 1994), the value of Gutierrez et al. 2005.
constexpr float kParticleG = 0.924f;

// Pure sea water: σa = a_w(λ), σs = b_w(λ) per unit concentration (1 = water), water lobe.
void makeWater(MediumComponent* c);
// CDOM: concentration = a_y(440) (1/m), σa = a_y(440) exp(−S(λ − 440)), no scattering (Case 2;
// Case 1 below).
void makeCdom(MediumComponent* c, float slopePerNm);
// Chlorophyll: concentration in mg/m³; σa = A(λ) C^(1−B(λ)), σs = 0.30 C^0.62 (550/λ), HG g.
void makeChlorophyll(MediumComponent* c, float g = kParticleG);

// Case-1 water: open-ocean water whose optical properties follow its chlorophyll alone, the
// dissolved organic matter included (Morel & Prieur 1977; Morel & Maritorena 2001, §2 and
// their absorption model, eq. 16, after Prieur & Sathyendranath 1981 and Morel 1991: yellow
// substance absorbs at 440 nm a fifth of what water and particles absorb there):
//     a_y(λ) = 0.2 [a_w(440) + a_p(440)] exp(−S (λ − 440)),   S = 0.014 1/nm,
// with a_p(440) = A(440) Chl^(1−B(440)), Mirage's own chlorophyll law (Bricaud et al. 1995),
// so that CDOM rises with chlorophyll as Morel 2009 reviews (his a_y(440) ∝ Chl^0.6 fits).
// At 0.03 mg/m³ a_y(440) is 0.0020 1/m, at 1 mg/m³ 0.0093, at 5 mg/m³ 0.025.
constexpr float kCase1CdomFraction = 0.2f;
// a_y(440) of Case-1 water at chlorophyll `chl` mg/m³ (1/m).
float case1CdomAbsorption440(float chl);
// Expands every cdom component that covaries with a chlorophyll component (covariesWith) into
// the two terms of a_y above: a constant 0.2 a_w(440) (under its own name) and a power law of
// the chlorophyll's grid and concentration, 0.2 A(440) C^(1−B(440)) (named NAME_chl). A cdom
// component whose concentration a scene or `--set` states is Case-2 water: the loaders clear
// its covariesWith first. Throws MirageError when covariesWith names no chlorophyll component.
void applyCase1Cdom(ShaderDesc* shader);

const char* componentKindName(ComponentKind kind);

}  // namespace mirage
