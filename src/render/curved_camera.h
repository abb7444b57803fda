// Camera rays that bend in a refractive-index field (mirages, heat haze): a decorator around any
// integrator. The camera ray follows its Fermat path (transport/curved_path.h) chord by chord
// until a chord meets a surface or `maxArc` of path is walked; media along the walked chords
// attenuate it (transmittance over arc length); the wrapped integrator then takes over with the
// last chord (when it met a surface) or the straight continuation. Radiance keeps L/n² along
// the path (the n² law).
//
// What it leaves out, until photons walk curved paths too (issue 5): light scattered by media
// inside the walked part (only their transmittance counts), and the bending of shadow rays from
// the surfaces it finds (they stay straight). For a road mirage or a sun behind a layered
// atmosphere seen across clear air, neither matters.
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
    std::string description;  // for `mirage info`
};

std::unique_ptr<Integrator> makeCurvedCameraIntegrator(std::unique_ptr<Integrator> inner,
                                                       std::shared_ptr<const Refraction> refraction);

}  // namespace mirage
