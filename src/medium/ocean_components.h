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
// CDOM: concentration = a_y(440) (1/m), σa = a_y(440) exp(−S(λ − 440)), no scattering.
void makeCdom(MediumComponent* c, float slopePerNm);
// Chlorophyll: concentration in mg/m³; σa = A(λ) C^(1−B(λ)), σs = 0.30 C^0.62 (550/λ), HG g.
void makeChlorophyll(MediumComponent* c, float g = kParticleG);

const char* componentKindName(ComponentKind kind);

}  // namespace mirage
