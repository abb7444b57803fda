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
// dissolved organic matter included (Morel & Prieur 1977). The absorption model of Morel &
// Maritorena (2001, after Prieur & Sathyendranath 1981 and Morel 1991) makes yellow substance
// absorb at 440 nm a fifth of what water and particles (phytoplankton and the detritus that
// co-varies with it) absorb there, with their published particle law:
//     a_y(λ) = 0.2 [a_w(440) + 0.06 Chl^0.65] exp(−S (λ − 440)),   S = 0.014 1/nm,
// Chl in mg/m³ (0.06 Chl^0.65 is Morel's a_p(440) in 1/m, A_Chl(440) = 1). a_w(440) is Mirage's
// own (Pope & Fry 1997, 0.00635 1/m, the value the model was published with). a_y(440) rises
// as Chl^0.65 once particles dominate: 0.0025 1/m at 0.03 mg/m³, 0.0040 at 0.1, 0.0133 at 1,
// 0.035 at 5. (Mirage's phytoplankton itself keeps Bricaud et al. 1995's law, which absorbs
// less at 440 nm than Morel's particles: 0.04 Chl^0.67 against 0.06 Chl^0.65.)
constexpr float kCase1CdomFraction = 0.2f;
constexpr float kCase1ParticleA440 = 0.06f;      // 1/m at 1 mg/m³
constexpr float kCase1ParticleExponent = 0.65f;  // a_p(440) ∝ Chl^0.65
// a_y(440) of Case-1 water at chlorophyll `chl` mg/m³ (1/m).
float case1CdomAbsorption440(float chl);
// Expands every cdom component that covaries with a chlorophyll component (covariesWith) into
// the two terms of a_y above: a constant 0.2 a_w(440) (under its own name) and a power law of
// the chlorophyll's grid and concentration, 0.2 · 0.06 C^0.65 (named NAME_chl). A cdom
// component whose concentration a scene or `--set` states is Case-2 water: the loaders clear
// its covariesWith first. Throws MirageError when covariesWith names no chlorophyll component.
void applyCase1Cdom(ShaderDesc* shader);

const char* componentKindName(ComponentKind kind);

}  // namespace mirage
