#include "film/aov.h"

#include <algorithm>

#include "core/error.h"
#include "core/text.h"

namespace mirage {

namespace {

const char* const kGroupPrefix = "lightgroup_";

const char* const kCryptoKinds[2] = {"volume", "shape"};

// What a pass name means, or false when it is none of the passes there are.
bool resolvePass(const std::string& name, const std::vector<std::string>& lightGroups,
                 const CryptoObjects& objects, AovPass* out) {
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
    // depth the sum of the finite depths and their count (the mean of those reaching 50 %);
    // variance the sums of the samples' products XY, XZ, YZ (the squares are the beauty's).
    struct Data {
        const char* name;
        AovKind kind;
        int doubles;
    };
    static const Data data[] = {{"alpha", AovKind::Alpha, 0},
                                {"depth", AovKind::Depth, 2},
                                {"albedo", AovKind::Albedo, 3},
                                {"transmittance", AovKind::Transmittance, 3},
                                {"variance", AovKind::Variance, 3}};
    for (const Data& d : data)
        if (name == d.name) {
            *out = {name, d.kind, 0, 0, d.doubles};
            return true;
        }
    // A Cryptomatte: one coverage sum per object of its kind.
    for (int k = 0; k < 2; ++k)
        if (name == cryptomattePass(kCryptoKinds[k])) {
            const size_t n = k == 0 ? objects.volumes.size() : objects.shapes.size();
            if (n == 0)
                throw MirageError("'" + name + "' asks for the Cryptomatte of every " +
                                  kCryptoKinds[k] + ", and the scene has no [[" + kCryptoKinds[k] +
                                  "]]");
            *out = {name, AovKind::Cryptomatte, k, 0, int(n)};
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
    for (const char* d : {"alpha", "depth", "albedo", "transmittance", "variance"})
        names.push_back(d);
    for (const char* k : kCryptoKinds) names.push_back(cryptomattePass(k));
    return names;
}

std::string cryptomattePass(const std::string& kind) {
    for (const char* k : kCryptoKinds)
        if (kind == k) return std::string("crypto_") + k;
    return "";
}

AovLayout::AovLayout(const std::vector<std::string>& names,
                     const std::vector<std::string>& lightGroups, const CryptoObjects& objects)
    : mNames(names), mLightGroups(lightGroups), mObjects(objects) {
    for (const std::string& name : names) {
        AovPass pass;
        if (!resolvePass(name, lightGroups, objects, &pass)) {
            const std::string groups = lightGroups.empty() ? " (no [[light]] has a group)" : "";
            throw MirageError("unknown AOV '" + name + "'; expected one of " +
                              joinList(aovNames(lightGroups)) +
                              (name.rfind(kGroupPrefix, 0) == 0 ? groups : ""));
        }
        if (std::any_of(mPasses.begin(), mPasses.end(),
                        [&](const AovPass& p) { return p.name == name; }))
            throw MirageError("AOV '" + name + "' is asked for twice");
        pass.offset = mStride;
        mStride += pass.doubles;
        placeOffset(pass);
        if (pass.kind == AovKind::LightGroup) mGroupSlots = int(lightGroups.size()) + 1;
        if (pass.kind == AovKind::Cryptomatte) mCoverage = true;
        if (pass.kind == AovKind::LightPath || pass.kind == AovKind::LightGroup)
            mSplitsRadiance = true;
        if (pass.kind == AovKind::Depth || pass.kind == AovKind::Albedo ||
            pass.kind == AovKind::Transmittance || mCoverage)
            mCameraData = true;
        mPasses.push_back(pass);
    }
}

void AovLayout::placeOffset(const AovPass& pass) {
    switch (pass.kind) {
        case AovKind::LightPath:
            mOffsets.path[size_t(pass.index)] = pass.offset;
            break;
        case AovKind::LightGroup:
            mOffsets.group.resize(mLightGroups.size() + 1, -1);
            mOffsets.group[size_t(pass.index)] = pass.offset;
            break;
        case AovKind::Depth:
            mOffsets.depth = pass.offset;
            break;
        case AovKind::Albedo:
            mOffsets.albedo = pass.offset;
            break;
        case AovKind::Transmittance:
            mOffsets.transmittance = pass.offset;
            break;
        case AovKind::Variance:
            mOffsets.variance = pass.offset;
            break;
        case AovKind::Cryptomatte:
            mOffsets.crypto[size_t(pass.index)] = pass.offset;
            break;
        case AovKind::Alpha:
            break;  // the beauty's own coverage sum
    }
}

// Both kinds' coverages whenever a Cryptomatte is asked for: a sample's alpha is shared among
// all the objects it met (scaleCoverage), whichever kinds are written.
AovSample::AovSample(const AovLayout& layout)
    : group(size_t(layout.groupSlots())), groupXyz(size_t(layout.groupSlots())) {
    if (!layout.coverage()) return;
    volumeCoverage.resize(layout.cryptoObjects().volumes.size());
    shapeCoverage.resize(layout.cryptoObjects().shapes.size());
}

void AovSample::scaleCoverage(float alpha) {
    float total = 0.f;
    for (float c : volumeCoverage) total += c;
    for (float c : shapeCoverage) total += c;
    if (!(total > 0.f)) {
        // The walk met no collision in thin smoke while the beauty's estimate saw opacity: the
        // medium the ray entered first holds it.
        if (alpha > 0.f && firstVolume >= 0) volumeCoverage[size_t(firstVolume)] = alpha;
        return;
    }
    const float k = alpha / total;
    for (float& c : volumeCoverage) c *= k;
    for (float& c : shapeCoverage) c *= k;
}

void AovSample::reset() {
    for (uint32_t m = litPaths; m != 0; m &= m - 1) {
        path[size_t(lowestBit(m))] = SampledSpectrum(0.f);
        pathXyz[size_t(lowestBit(m))] = Vec3(0.f);
    }
    if (groupsLit) {
        std::fill(group.begin(), group.end(), SampledSpectrum(0.f));
        std::fill(groupXyz.begin(), groupXyz.end(), Vec3(0.f));
    }
    litPaths = 0;
    groupsLit = false;
    depth = kInfinity;
    albedo = SampledSpectrum(0.f);
    transmittance = SampledSpectrum(1.f);
    std::fill(volumeCoverage.begin(), volumeCoverage.end(), 0.f);
    std::fill(shapeCoverage.begin(), shapeCoverage.end(), 0.f);
    firstVolume = -1;
}

void AovSample::addWeighted(const AovSample& o, const SampledSpectrum& T, float k) {
    litPaths |= o.litPaths;
    groupsLit = groupsLit || o.groupsLit;
    for (size_t p = 0; p < path.size(); ++p) {
        path[p] += o.path[p] * T * k;
        pathXyz[p] += o.pathXyz[p] * k;
    }
    for (size_t g = 0; g < group.size(); ++g) {
        group[g] += o.group[g] * T * k;
        groupXyz[g] += o.groupXyz[g] * k;
    }
}

}  // namespace mirage
