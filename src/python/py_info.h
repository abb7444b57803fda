// The record of `mirage info` for Python: scene.info() returns it as nested dicts.
#pragma once

#include <pybind11/pybind11.h>

#include "scene/scene_info.h"

namespace mirage::python {

// `info` as a dict: volumes (grids, slots, expressions, velocity, emission, majorant), lights,
// camera, shutter, film, integrator and why, colour management, output, and the physics terms
// keyed by name ({"active": bool, "why": str}).
pybind11::dict infoDict(const SceneInfo& info);

}  // namespace mirage::python
