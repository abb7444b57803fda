// The photon estimators' convergence scene, shared by the one-map and the progressive tests.
#pragma once

#include "render/render_scene.h"

namespace mirage::test {

// A 1 m cube of uniform fog (σa 0.4, σs 4 per unit density, HG g 0.3) under a white sun of
// 1000 W/m², seen from the front.
RenderScene fogBoxScene();

}  // namespace mirage::test
