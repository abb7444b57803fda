// The procedural assets of `mirage make-asset` as OpenVDB files (the demo and the unit tests
// make their own grids instead of shipping data). This header does not include OpenVDB;
// asset_writer.cpp does.
//
// Files are written atomically: to a temporary file in the destination folder, then renamed
// over the destination, so a failed or interrupted write never leaves a partial .vdb behind.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/procedural_fields.h"

namespace mirage {

// The range of `resolution`, voxels along an asset's 2 m height.
constexpr int kMinAssetResolution = 8, kMaxAssetResolution = 4096;

// Writes a procedural OpenVDB asset to `path` (the fields are procedural_fields.cpp's). All grids
// are float fog volumes (background 0, only non-zero voxels active), y is up, the asset is 2 m tall
// and stands on y = 0 centred on the y axis; `resolution` is the number of voxels along the height
// (8 to 4096), so the voxel size is 2 m / resolution. The content is a pure function of (kind,
// resolution, seed): the noise is Mirage's own hash-based gradient noise, not a platform random
// engine, and the grids do not depend on the thread count.
//   "smoke"      a noise-modulated rising plume, 1.2 m wide. `density` (unitless, ≤ ~1.3; a
//                shader scales it into σ), `temperature` (K): ~300 K ambient at the plume's
//                edge rising to ~900 K in its core near the source, 0 outside the plume.
//   "fire"       flames rising from a 0.6 m wide base into smoke, 1 m wide. `flame` (0..1
//                reaction intensity), `temperature` (K) up to ~1800 K in the flames, ~300–700 K
//                in the smoke, `density` (soot, unitless, ≤ ~1).
//   Both also write `vel` (vec3s, collocated, m/s) over the density's voxels: the plume's
//   updraft (~1.2 m/s for smoke, up to ~3 m/s in the flames), its spreading and a swirl about
//   its axis (0.3 m/s at the edge), for velocity motion blur.
//   "fog-sphere" `density` of a soft sphere centred at (0, 1, 0) m: 1 within 0.6 m of the
//                centre, falling smoothly (smoothstep) to 0 at 1 m. Analytic; the seed is
//                unused.
//   "ocean"      `chlorophyll` (mg/m³ of chlorophyll a, for the `ocean` shader's slot): a
//                patchy phytoplankton plume rising from a 0.6 m wide patch on the floor and
//                widening to ~1.4 m, up to ~10 mg/m³ in its core, 0 (clear water) outside.
//   "pyro"       a billowing column filling a quarter of its 1.6 × 2 × 1.6 m box, for
//                production-sized caches (10^9 active voxels at resolution ~1800): `density`,
//                `temperature` (K, in the core) and `vel` at twice the voxel size, all stored
//                as half floats (procedural_fields.cpp describes it).
// The 8³ blocks of voxels are evaluated in parallel (TBB) and skipped where a field says they
// are empty; `report` shows a progress bar (core/progress.h) on stderr.
// Throws MirageError for an unknown kind (listing the valid ones), a bad resolution, or a file
// that cannot be written.
void writeProceduralAsset(const std::string& kind, const std::string& path, int resolution = 64,
                          uint64_t seed = 1, bool report = false);

// The resolution at which asset `kind` has about `voxels` active voxels in its first grid
// (measured at a small resolution and scaled as resolution³), within the range above.
int assetResolutionForVoxels(const std::string& kind, uint64_t seed, double voxels);

}  // namespace mirage
