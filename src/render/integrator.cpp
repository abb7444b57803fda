#include "render/integrator.h"

#include "core/error.h"
#include "core/text.h"
#include "render/photon_integrator.h"

namespace mirage {

const std::vector<IntegratorInfo>& integratorInfos() {
    static const std::vector<IntegratorInfo> infos = {
        {"single", "single scattering + emission", false, false},
        {"volpath", "the reference spectral volumetric path tracer", true, false, true},
        {"photon", "volume photon mapping: single scattering + photon-map multiple scattering",
         true, true},
    };
    return infos;
}

std::string integratorNameList() {
    return joinList(integratorInfos(), [](const IntegratorInfo& i) { return i.name; });
}

const IntegratorInfo& integratorInfo(const std::string& name) {
    for (const IntegratorInfo& i : integratorInfos())
        if (i.name == name) return i;
    throw MirageError("unknown integrator '" + name +
                      "'; expected one of: " + integratorNameList());
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth) {
    return makeIntegrator(name, maxDepth, PhotonIntegratorSettings());
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, int maxDepth,
                                           const PhotonIntegratorSettings& photon) {
    const IntegratorInfo& info = integratorInfo(name);
    if (info.photonPass) {
        PhotonIntegratorSettings s = photon;
        s.maxBounces = maxDepth;
        return makePhotonIntegrator(s);
    }
    return info.multipleScattering ? makeVolPathIntegrator(maxDepth)
                                   : makeSingleScatterIntegrator();
}

}  // namespace mirage
