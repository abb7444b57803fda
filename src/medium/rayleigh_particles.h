// Particles much smaller than the wavelength (d ≪ λ) scatter as Rayleigh found: the
// cross-section of a sphere of diameter d and relative refractive index n is
//     C_s(λ) = (2π⁵/3) · d⁶/λ⁴ · ((n² − 1)/(n² + 2))²
// (Rayleigh 1871; Bohren & Huffman 1983, §5.2, with the radius a = d/2 and k = 2π/λ:
// (8π/3) k⁴ a⁶ ((n² − 1)/(n² + 2))²), so that N particles per m³ scatter σs = N·C_s, with the
// Rayleigh lobe 3/(16π)(1 + cos²θ) and no absorption (a real index). What `kind = "rayleigh"`
// in a shader file means: the component's concentration (× grid) then scales N.
#pragma once

#include "medium/shader.h"

namespace mirage {

// C_s in m² for d and λ in metres.
double rayleighCrossSection(double diameterM, double index, double lambdaM);
// σs(λ) = N·C_s(λ) per unit concentration, σa = 0, the Rayleigh lobe. d in nm.
void makeRayleighParticles(MediumComponent* c, double diameterNm, double index,
                           double numberDensity);

}  // namespace mirage
