#include "render/integrator.h"

#include "core/error.h"
#include "core/text.h"
#include "film/exr_header.h"

namespace mirage {

std::vector<std::pair<std::string, std::string>> PhotonStats::metadata() const {
    return {{"photons_traced", std::to_string(photonsTraced)},
            {"photons_stored", std::to_string(photonsStored)},
            {"photon_pass_seconds", headerNumber(photonPassSeconds)},
            {"photons_per_second", headerNumber(photonsPerSecond)},
            {"photon_map_build_seconds", headerNumber(photonMapBuildSeconds)},
            {"photon_radii_seconds", headerNumber(photonRadiiSeconds)},
            {"disc_bvh_build_seconds", headerNumber(discBvhBuildSeconds)},
            {"estimate_seconds", headerNumber(estimateSeconds)}};
}

bool photonsCurve(const IndexField* field, const Bounds3& b) {
    if (!field || b.empty()) return false;
    const Vec3 pad = b.diagonal() * 0.1f;
    return field->gradientBound(Vec3d(b.lo - pad), Vec3d(b.hi + pad)) > 0.0;
}

const std::vector<IntegratorInfo>& integratorInfos() {
    static const std::vector<IntegratorInfo> infos = {
        {"single", "single scattering + emission", false, false},
        {"volpath", "the reference spectral volumetric path tracer", true, false},
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
    throw MirageError("unknown integrator '" + name + "'; expected one of: " +
                      integratorNameList());
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
