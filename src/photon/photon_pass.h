// The photon pass (Jensen & Christensen 1998, with the full RTE of Gutierrez et al. 2005):
// photons are emitted from the lights in proportion to their power, fly by delta tracking
// through the media, and at each real collision an albedo roulette decides between scattering
// (new direction from the phase function, power unchanged) and absorption. Scattering events
// are stored as volume photons. Parallel and deterministic: photon i's random numbers depend
// only on (seed, i), and the stored list is ordered by photon index.
#pragma once

#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "light/light.h"
#include "medium/medium.h"
#include "photon/photon.h"

namespace mirage {

struct PhotonPassSettings {
    uint64_t photons = 100000;  // photons emitted, over all lights
    uint64_t seed = 0;
    int maxBounces = 10000;     // cap on scattering events per photon (capped paths counted)
    // When the render pass computes single scattering by shadow rays, the first interaction
    // of each photon must not be stored, or direct light would be counted twice.
    bool storeFirstInteraction = false;
    Progress::Mode progress = Progress::Mode::Auto;
};

struct PhotonPassStats {
    uint64_t emitted = 0, stored = 0, cappedPaths = 0;
    double seconds = 0;
};

PhotonList tracePhotons(const std::vector<const Light*>& lights,
                        const std::vector<const Medium*>& media, const PhotonPassSettings& settings,
                        PhotonPassStats* stats);

}  // namespace mirage
