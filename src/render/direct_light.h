// Next-event estimation at a medium scattering point, shared by every integrator: each light
// is sampled once and its contribution is attenuated by a ratio-tracked shadow ray.
#pragma once

#include "render/integrator.h"

namespace mirage {

// Σ_lights p(−wi, wo) · Li · T(shadow ray). wo is the direction the light leaves towards the
// viewer (the reverse of the incoming path direction).
SampledSpectrum directLightMedium(const RenderScene& scene, const Collision& c, const Vec3& wo,
                                  Sampler& sampler, ThreadState& ts);

}  // namespace mirage
