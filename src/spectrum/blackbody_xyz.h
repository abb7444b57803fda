// The colour of blackbody radiance as the film sees it, without sampling wavelengths.
//
// A grey medium that glows by Kirchhoff's law (Le = intensity · B(λ, T), medium/shader.h) adds
// at each emission event a factor free of λ times B(λ, T): its exact XYZ is that factor times
// XYZ[B(·, T)], the expectation of the film's per-sample estimate over the sample's
// wavelengths (a conditional expectation, as render/achromatic_film.h does for lights). Filmed
// so, fire in grey smoke has no colour noise from the four wavelengths a sample carries.
#pragma once

#include "core/math.h"

namespace mirage {

// XYZ of B(λ, T) in W·m⁻²·sr⁻¹·nm⁻¹ (Planck × 1e-9), as spectrumToXyz sums a spectrum
// (spectrum/spectrum.h): tabulated at 256 temperatures log-spaced over 300–100 000 K and
// interpolated by cubics in (ln T, ln X, ln Y, ln Z) (relative error below 1e-5; the
// BlackbodyXyz test); summed directly outside that range. 0 for T ≤ 0.
Vec3 blackbodyXyz(float kelvin);

}  // namespace mirage
