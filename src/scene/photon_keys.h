// The photon integrator's keys of [render] (docs/scene-file.md): photons per map and the first
// map's, the estimate and its width, the final gather, and the projection maps' caustic stream.
#pragma once

#include "scene/scene.h"
#include "scene/toml_reader.h"

namespace mirage {

// Reads them from `r` (the [render] table) into scene->photon, and what the scene stated.
void readPhotonKeys(const TableReader& r, Scene* scene);

}  // namespace mirage
