// The photon integrator's keys of [render] (photon_keys.h).
#include "scene/photon_keys.h"

#include "render/photon_integrator.h"

namespace mirage {

void readPhotonKeys(const TableReader& r, Scene* scene) {
    scene->photon.photons = uint64_t(r.getInt("photons", 100000, 0, int64_t(1) << 40));
    if (r.has("photons")) scene->statedPhotons = scene->photon.photons;
    scene->photon.firstPassPhotons =
        uint64_t(r.getInt("first_pass_photons", 0, 0, int64_t(1) << 40));
    scene->statedFirstPassPhotons = r.has("first_pass_photons");
    scene->photon.estimate = r.getChoice("estimate", "beam", "point", "photon estimate")
                                 ? PhotonEstimate::Beam
                                 : PhotonEstimate::Point;
    scene->photon.k = int(r.getInt("k", 0, 0, 1 << 16));
    if (scene->photon.k == 1)
        r.fail("k",
               "expected 0 (the default for the estimate) or at least 2 photons: a "
               "density from one neighbour has no finite mean");
    scene->photon.maxRadius = float(r.getNumber("max_radius", 0.0, 0.0, 1e12));
    scene->photon.finalGather =
        int(r.getInt("final_gather", kDefaultFinalGather, 0, kMaxFinalGather));
    // Projection maps (photon/projection_map.h): off (the default) or on; caustic_photons 0:
    // as many as photons.
    scene->photon.projection = r.getChoice("projection", "off", "on", "projection")
                                   ? PhotonPassSettings::Projection::Off
                                   : PhotonPassSettings::Projection::On;
    scene->photon.causticPhotons = uint64_t(r.getInt("caustic_photons", 0, 0, int64_t(1) << 40));
}

}  // namespace mirage
