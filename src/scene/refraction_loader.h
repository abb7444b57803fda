// The scene file's [refraction] table: a refractive-index field that bends camera rays
// (render/curved_camera.h).
//
//   [refraction]
//   profile = "atmosphere"     # "linear": n = n0 + k·y | "atmosphere": US Standard Atmosphere 1976
//   n0 = 1.0                   # linear
//   k = 0.0                    # linear, 1/m
//   ground_height = 0.0        # atmosphere: the scene y of sea level, m
//   tolerance = 1e-6           # Dormand–Prince error tolerance per step
//   max_step = 5.0             # m; 0 = unlimited (keep it below the thinnest layer)
//   max_distance = 1000.0      # m of curved path per camera ray; straight beyond
//   [[refraction.inversion]]   # atmosphere: a layer delta_t kelvin warmer between base and top
//   base = -2.0
//   top = 0.5
//   delta_t = 30.0
//   blend = 1.0                # m over which each edge blends in
#pragma once

#include <memory>

#include "render/curved_camera.h"
#include "scene/toml_reader.h"

namespace mirage {

std::shared_ptr<const Refraction> readRefraction(const TableReader& table);

}  // namespace mirage
