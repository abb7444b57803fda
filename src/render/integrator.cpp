#include "render/integrator.h"

#include "core/error.h"

namespace mirage {

std::vector<std::string> integratorNames() { return {"single", "volpath", "photon"}; }

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth,
                                           const PhotonIntegratorSettings& photon) {
    if (name == "single") return makeSingleScatterIntegrator();
    if (name == "volpath") return makeVolPathIntegrator(maxDepth);
    if (name == "photon") {
        PhotonIntegratorSettings s = photon;
        s.maxBounces = maxDepth;
        return makePhotonIntegrator(s);
    }
    std::string list;
    for (const auto& n : integratorNames()) list += (list.empty() ? "" : ", ") + n;
    throw MirageError("unknown integrator '" + name + "'; expected one of: " + list);
}

}  // namespace mirage
