// Next-event estimation at an inelastic (fluorescent) vertex of a camera path. Re-emission is
// isotropic (reemission.h), so the vertex's lobe is 1/(4π) whatever the medium's elastic phase
// functions are: Σ_lights Li(λ) · T(shadow ray) / (4π), at the tracking context's wavelengths
// (the absorbed wavelength λi, to which the path has switched).
#pragma once

#include "render/integrator.h"

namespace mirage {

SampledSpectrum directLightIsotropic(const RenderScene& scene, const Vec3& p, Sampler& sampler,
                                     ThreadState& ts);

}  // namespace mirage
