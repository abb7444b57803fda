// Camera rays that bend in a refractive-index field (mirages, heat haze): a decorator around any
// integrator. The camera ray follows its Fermat path (transport/curved_path.h) chord by chord
// until a chord meets a surface or `maxArc` of path is walked. On every chord that crosses a
// medium's bounds the wrapped integrator estimates what the media emit and scatter towards the
// chord (its ray stopped at the chord's end), and the chord's transmittance over arc length
// attenuates everything beyond; the wrapped integrator then takes the last chord (when it met a
// surface) or the straight continuation. Radiance keeps L/n² along the path (the n² law).
// A path stopped by the ODE step cap (CurvedPathSettings::maxSteps) also goes on straight, and
// is counted in cappedPaths() (the render summary's and the EXR's capped paths).
//
// The wrapped single and volpath integrators bend the rest of their paths too: the decorator
// hands them the field (render/curved_transport.h, through ThreadState::curved), and their
// shadow rays towards lights at infinity (render/direct_light.cpp) and volpath's scattered
// segments follow Fermat paths; shadow rays towards lamps at a finite distance stay straight
// (direct_light.cpp says why). The photon integrator bends photons (photon/photon_pass.h) and
// takes direct light from the photon maps, as Gutierrez et al. 2005 do where paths curve.
#pragma once

#include <memory>
#include <string>

#include "medium/index_field.h"
#include "render/integrator.h"
#include "transport/curved_path.h"

namespace mirage {

struct Refraction {
    std::shared_ptr<const IndexField> field;
    CurvedPathSettings path;  // tolerance, maxStep, …
    float maxArc = 1000.f;    // m of curved path per camera ray; straight beyond
    // single and volpath: shadow rays to lights at infinity and scattered segments bend too
    // (render/curved_transport.h); false: camera rays alone (the cheaper approximation).
    bool bendTransport = true;
    std::string description;  // for `mirage info`
};

std::unique_ptr<Integrator> makeCurvedCameraIntegrator(
    std::unique_ptr<Integrator> inner, std::shared_ptr<const Refraction> refraction);

}  // namespace mirage
