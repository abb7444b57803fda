#include "film/aov.h"

#include <algorithm>

#include "core/error.h"
#include "core/text.h"

namespace mirage {

namespace {

const char* const kGroupPrefix = "lightgroup_";

// What a pass name means, or false when it is none of the passes there are.
bool resolvePass(const std::string& name, const std::vector<std::string>& lightGroups,
                 AovPass* out) {
    for (int p = 0; p < kLightPathCount; ++p)
        if (name == lightPathName(LightPath(p))) {
            *out = {name, AovKind::LightPath, p, 0, 3};
            return true;
        }
    if (name == std::string(kGroupPrefix) + "emission") {
        *out = {name, AovKind::LightGroup, kEmissionGroup, 0, 3};
        return true;
    }
    for (size_t g = 0; g < lightGroups.size(); ++g)
        if (name == kGroupPrefix + lightGroups[g]) {
            *out = {name, AovKind::LightGroup, int(g) + 1, 0, 3};
            return true;
        }
    // Data passes and the sums each keeps per pixel: alpha is the beauty's own coverage sum;
    // depth the sum of the finite depths and their count (the mean of those reaching 50 %).
    struct Data {
        const char* name;
        AovKind kind;
        int doubles;
    };
    static const Data data[] = {{"alpha", AovKind::Alpha, 0},
                                {"depth", AovKind::Depth, 2},
                                {"albedo", AovKind::Albedo, 3},
                                {"transmittance", AovKind::Transmittance, 3}};
    for (const Data& d : data)
        if (name == d.name) {
            *out = {name, d.kind, 0, 0, d.doubles};
            return true;
        }
    return false;
}

}  // namespace

std::vector<std::string> aovNames(const std::vector<std::string>& lightGroups) {
    std::vector<std::string> names;
    for (int p = 0; p < kLightPathCount; ++p) names.push_back(lightPathName(LightPath(p)));
    names.push_back(std::string(kGroupPrefix) + "emission");
    for (const std::string& g : lightGroups) names.push_back(kGroupPrefix + g);
    for (const char* d : {"alpha", "depth", "albedo", "transmittance"}) names.push_back(d);
    return names;
}

AovLayout::AovLayout(const std::vector<std::string>& names,
                     const std::vector<std::string>& lightGroups)
    : mNames(names), mLightGroups(lightGroups) {
    for (const std::string& name : names) {
        AovPass pass;
        if (!resolvePass(name, lightGroups, &pass)) {
            // The per-pixel variance belongs with adaptive sampling's second moments.
            const std::string why =
                name == "variance" ? " (the variance pass is not available yet)" : "";
            const std::string groups = lightGroups.empty() ? " (no [[light]] has a group)" : "";
            throw MirageError("unknown AOV '" + name + "'" + why + "; expected one of " +
                              joinList(aovNames(lightGroups)) +
                              (name.rfind(kGroupPrefix, 0) == 0 ? groups : ""));
        }
        if (std::any_of(mPasses.begin(), mPasses.end(),
                        [&](const AovPass& p) { return p.name == name; }))
            throw MirageError("AOV '" + name + "' is asked for twice");
        pass.offset = mStride;
        mStride += pass.doubles;
        if (pass.kind == AovKind::LightGroup) mGroupSlots = int(lightGroups.size()) + 1;
        if (pass.kind == AovKind::Depth || pass.kind == AovKind::Albedo ||
            pass.kind == AovKind::Transmittance)
            mCameraData = true;
        mPasses.push_back(pass);
    }
}

void AovSample::reset() {
    path.fill(SampledSpectrum(0.f));
    pathXyz.fill(Vec3(0.f));
    std::fill(group.begin(), group.end(), SampledSpectrum(0.f));
    depth = kInfinity;
    albedo = SampledSpectrum(0.f);
    transmittance = SampledSpectrum(1.f);
}

void AovSample::addWeighted(const AovSample& o, const SampledSpectrum& T, float k) {
    for (size_t p = 0; p < path.size(); ++p) {
        path[p] += o.path[p] * T * k;
        pathXyz[p] += o.pathXyz[p] * k;
    }
    for (size_t g = 0; g < group.size(); ++g) group[g] += o.group[g] * T * k;
}

}  // namespace mirage
