// Render passes (AOVs): which ones a render asks for (AovLayout), what one camera sample
// carries into them (AovSample), and the layers they develop into (docs/aovs.md).
//
// Light-path passes and light groups are spectral like the beauty: each sample's radiance is
// split by the integrator at the one place it is added (core/light_path.h, render/integrator.h
// RadianceSample::add), and the film reduces every part to XYZ with the beauty's own estimator,
// so that the parts sum to the beauty up to float rounding. Data passes describe the camera ray
// (render/camera_ray_data.h): its transmittance, the opacity-weighted albedo of what it meets,
// and the depth where its opacity first reaches one half. The variance pass is the variance of
// the beauty's pixel mean (film/film_error.h), from the film's sums of the samples' squares and
// products.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/light_path.h"
#include "core/math.h"
#include "core/spectral.h"

namespace mirage {

enum class AovKind {
    LightPath,
    LightGroup,
    Alpha,
    Depth,
    Albedo,
    Transmittance,
    Variance,
    Cryptomatte
};

// One pass: its layer name (and EXR channel prefix), what it holds, and where its sums sit in
// a pixel's AOV record.
struct AovPass {
    std::string name;
    AovKind kind;
    int index = 0;    // LightPath: the class; LightGroup: the group slot (0 = emission);
                      // Cryptomatte: 0 volumes, 1 shapes
    int offset = 0;   // first double of the pass in the pixel's record
    int doubles = 0;  // sums the pass keeps per pixel
};

// The slot of light emitted by media and surfaces among the light groups.
constexpr int kEmissionGroup = 0;

// The objects a Cryptomatte names (film/cryptomatte.h; [[volume]] and [[shape]] name): the
// volumes in the order of the scene's media, the shapes in the order of its shapes. The passes
// crypto_volume and crypto_shape keep one coverage sum per object.
struct CryptoObjects {
    std::vector<std::string> volumes, shapes;
};

// Where each pass's sums sit in a pixel's record, by what it holds (-1: not asked for), so that
// the film adds a sample's passes without looking their kinds up.
struct AovOffsets {
    std::array<int, kLightPathCount> path;
    std::vector<int> group;  // per light-group slot
    int depth = -1, albedo = -1, transmittance = -1, variance = -1;
    std::array<int, 2> crypto{-1, -1};  // volumes, shapes

    AovOffsets() { path.fill(-1); }
};

class AovLayout {
public:
    AovLayout() = default;
    // The passes `names` asks for, in that order. `lightGroups` are the scene's groups
    // ([[light]] group); slot 0 is `lightgroup_emission`, slot g + 1 lightGroups[g]; `objects`
    // the names crypto_volume and crypto_shape give their objects. Throws MirageError naming
    // the pass and the passes there are, for an unknown or repeated name.
    AovLayout(const std::vector<std::string>& names, const std::vector<std::string>& lightGroups,
              const CryptoObjects& objects = {});

    bool empty() const { return mPasses.empty(); }
    // What it was made from (a partial file stores them to make it again).
    const std::vector<std::string>& names() const { return mNames; }
    const std::vector<std::string>& lightGroups() const { return mLightGroups; }
    const CryptoObjects& cryptoObjects() const { return mObjects; }
    const std::vector<AovPass>& passes() const { return mPasses; }
    const AovOffsets& offsets() const { return mOffsets; }
    int stride() const { return mStride; }  // doubles per pixel
    // Light-group slots a sample carries: 1 + the scene's groups when a group pass is asked
    // for, else 0 (the groups are then not split at all).
    int groupSlots() const { return mGroupSlots; }
    // Whether the camera ray's data (depth, albedo, transmittance, coverage) must be computed.
    bool cameraData() const { return mCameraData; }
    // Whether a sample carries each object's coverage (a Cryptomatte is asked for).
    bool coverage() const { return mCoverage; }
    // Whether a pass splits the beauty's radiance (light paths, light groups), so that each
    // sample's spectral radiance must reach the film as it is, to sum to the beauty exactly.
    bool splitsRadiance() const { return mSplitsRadiance; }

private:
    void placeOffset(const AovPass& pass);

    std::vector<std::string> mNames, mLightGroups;
    CryptoObjects mObjects;
    std::vector<AovPass> mPasses;
    AovOffsets mOffsets;
    int mStride = 0;
    int mGroupSlots = 0;
    bool mCameraData = false;
    bool mCoverage = false;
    bool mSplitsRadiance = false;
};

// Every pass name a scene with these light groups may ask for, for messages and --help.
std::vector<std::string> aovNames(const std::vector<std::string>& lightGroups);

// The pass of the Cryptomatte of `kind` ("volume", "shape": [output] cryptomatte), or "" for
// another kind.
std::string cryptomattePass(const std::string& kind);

// What one camera sample adds to the passes. Spectral parts at the sample's wavelengths, XYZ
// parts from the photon estimates (each photon at its own wavelength). A sample's light is
// mostly of one or two light paths, so the parts it touched are marked (litPaths, groupsLit),
// and the film, reset() and forEachRadiance visit only those.
struct AovSample {
    std::array<SampledSpectrum, kLightPathCount> path;
    std::array<Vec3, kLightPathCount> pathXyz;
    std::vector<SampledSpectrum> group;  // groupSlots() entries
    std::vector<Vec3> groupXyz;          // the photon estimates' groups, groupSlots() entries
    float depth = kInfinity;             // m along the camera ray; ∞: never 50 % opaque
    SampledSpectrum albedo;              // ∫ T σs dt + T(surface) ρ(surface)
    SampledSpectrum transmittance{1.f};
    // Each object's share of the sample's coverage (Cryptomatte), when the layout asks; the
    // medium the camera ray enters first, which takes the coverage a walk without collisions
    // did not place (−1: none).
    std::vector<float> volumeCoverage, shapeCoverage;
    int firstVolume = -1;
    uint32_t litPaths = 0;   // bit p: path[p] or pathXyz[p] was added to
    bool groupsLit = false;  // a light group was added to

    AovSample() = default;
    explicit AovSample(const AovLayout& layout);
    void reset();
    void addPath(const SampledSpectrum& c, LightPath p) {
        path[size_t(p)] += c;
        litPaths |= 1u << unsigned(p);
    }
    void addGroup(const SampledSpectrum& c, int slot) {
        if (group.empty()) return;
        group[size_t(slot)] += c;
        groupsLit = true;
    }
    // Next-event estimation's light split by group (ThreadState::lightSplit), at throughput beta.
    void addGroups(const SampledSpectrum& beta, const std::vector<SampledSpectrum>& split) {
        if (group.empty()) return;
        for (size_t g = 0; g < group.size(); ++g) group[g] += beta * split[g];
        groupsLit = true;
    }
    void addPathXyz(const Vec3& c, LightPath p) {
        pathXyz[size_t(p)] += c;
        litPaths |= 1u << unsigned(p);
    }
    // A photon estimate's parts per light group (photon/photon_groups.h), groupSlots() of them.
    void addGroupXyz(const std::vector<Vec3>& parts) {
        if (groupXyz.empty()) return;
        for (size_t g = 0; g < groupXyz.size(); ++g) groupXyz[g] += parts[g];
        groupsLit = true;
    }
    // Applies f to every spectral radiance part that holds light (a path's final estimate, a
    // chord's weight; f maps 0 to 0).
    template <typename F>
    void forEachRadiance(F&& f) {
        for (uint32_t m = litPaths; m != 0; m &= m - 1) f(path[size_t(lowestBit(m))]);
        if (groupsLit)
            for (SampledSpectrum& s : group) f(s);
    }
    static int lowestBit(uint32_t m) { return __builtin_ctz(m); }
    // Scales the objects' coverages to sum to the sample's alpha (render/camera_ray_data.h).
    void scaleCoverage(float alpha);
    // Adds `o` weighted by T (spectral parts) and k (all radiance parts): the curved camera's
    // chords (render/curved_camera.cpp).
    void addWeighted(const AovSample& o, const SampledSpectrum& T, float k);
};

}  // namespace mirage
