// The scene file's [refraction] table: a refractive-index field that bends camera rays
// (render/curved_camera.h).
//
//   [refraction]
//   profile = "atmosphere"     # "linear": n = n0 + k·y | "atmosphere": US Standard Atmosphere 1976
//                              # | "grid": a volume's temperature grid (heat haze)
//   n0 = 1.0                   # linear
//   k = 0.0                    # linear, 1/m
//   ground_height = 0.0        # atmosphere: the scene y of sea level, m
//   earth = "flat"             # atmosphere: "flat" layers y = const, or "round": spherical
//                              # shells about (0, ground_height − earth_radius, 0)
//   earth_radius = 6371000.0   # round: m
//   shell_depth = 40000.0      # round: m of air; n = 1 above it (its last km fades)
//   dispersion = "cauchy"      # atmosphere: the paper's Cauchy a(1 + b/λ²) | "edlen" (1966)
//                              # | "ciddor" (1996), each scaled by density (air_dispersion.h)
//   tolerance = 1e-6           # Dormand–Prince error tolerance per step
//   max_step = 5.0             # m; 0 = unlimited (keep it below the thinnest layer)
//   max_distance = 1000.0      # m of curved path per camera ray; straight beyond
//   max_steps = 10000000       # ODE steps (accepted + rejected) per path; a path that reaches
//                              # it goes on straight, counted in the capped paths
//   surface_step_cap = true    # shorter steps where a path nears a surface
//                              # (transport/surface_step_cap.h); false: only max_step
//   [[refraction.inversion]]   # atmosphere: a layer delta_t kelvin warmer between base and top
//   base = -2.0
//   top = 0.5
//   delta_t = 30.0
//   blend = 1.0                # m over which each edge blends in (fermi: the width a)
//   edge = "smooth"            # the C² step over blend | "fermi": 1/(1 + e^(−(z − edge)/a))
//   volume = 0                 # grid: index of the [[volume]]
//   grid = "temperature"       # grid: its shader's slot (default: the emission temperature slot)
//   ambient = 288.15           # grid: K of the air around the flames
//   temperature_scale = 1.0    # grid: T = max(ambient, offset + scale·value); default: the
//   temperature_offset = 0.0   #       shader's emission mapping
#pragma once

#include <memory>
#include <vector>

#include "medium/medium.h"
#include "render/curved_camera.h"
#include "scene/toml_reader.h"

namespace mirage {

// `media` are the scene's volumes, for profile = "grid".
std::shared_ptr<const Refraction> readRefraction(const TableReader& table,
                                                 const std::vector<std::unique_ptr<Medium>>& media);

}  // namespace mirage
