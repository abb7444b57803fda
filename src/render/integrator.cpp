#include "render/integrator.h"

#include <cstdio>

#include "core/error.h"
#include "core/text.h"

namespace mirage {

std::vector<std::pair<std::string, std::string>> PhotonStats::metadata() const {
    auto num = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", v);
        return std::string(buf);
    };
    return {{"photons_traced", std::to_string(photonsTraced)},
            {"photons_stored", std::to_string(photonsStored)},
            {"photon_pass_seconds", num(photonPassSeconds)},
            {"photons_per_second", num(photonsPerSecond)},
            {"photon_map_build_seconds", num(photonMapBuildSeconds)},
            {"photon_radii_seconds", num(photonRadiiSeconds)},
            {"disc_bvh_build_seconds", num(discBvhBuildSeconds)},
            {"estimate_seconds", num(estimateSeconds)}};
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
