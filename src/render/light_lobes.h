// Where the light is, for paths in strongly forward media (sea water's particles, HG g 0.92:
// p(0) = 26/sr against a mean of 1/4π): lobes about the directions towards the lights, which
// the path tracer's lobe walks draw from (render/volpath.cpp, "Lobe walks").
//
// Why. A medium vertex's next-event estimate scores p(θ) of the angle between the path's last
// segment and the light. In such a medium the light seen just past the forward lobe — an
// aureole about a lamp, a glow about the sun's beam — is bright and narrow, and a path finds it
// only when its phase or cosine sample happens to point at the light: rare, bright samples,
// the speckles of the Cornell-water and underwater scenes. Drawing directions from lobes about
// the lights finds it at the lobes' density.
// Not used (plain sampling, the same random numbers as before) where no medium of the scene
// peaks above 5/sr (HG g ≳ 0.82): smoke, fog and clouds keep their paths.
#pragma once

#include <array>

#include "render/integrator.h"

namespace mirage {

// Whether any medium of the scene is forward enough for guiding, and a light to guide to (a
// light not at infinity, or a sun in a sky map: Light::lobe).
bool guidesPaths(const RenderScene& scene);

// The probability that a medium vertex of a guided path starts a lobe walk: 1 where paths are
// short, 25 (1 − ρ) within [0.1, 1] with ρ the highest single-scattering albedo of any
// medium component (σs / (σa + σs) of its spectra's peaks). A path in a medium of albedo ρ meets
// about 1/(1 − ρ) vertices, each walk costs about four next-event estimates (it goes on past each
// vertex with probability ¾), so a cloud of albedo 0.99 starting a walk at every vertex paid 4.2×
// the lookups of unguided paths; starting one at a quarter of them (about 25 a path) reached a
// given error in about half the time of walks at every vertex (sky-hdr regime, docs/regimes.md).
// Sea water (ρ ≲ 0.9) keeps a walk at every vertex.
float lobeWalkStart(const RenderScene& scene);

// Lobes (HG g 0.9) about the directions from a point towards the lights not at infinity (at
// most four; a distant light's direction, a point's, about a quad's middle), each chosen in
// proportion to the light that would arrive unblocked (its sample's mean Li/pdf at (½, ½)), so
// that a lamp in the next room of a scene draws few directions: the guide's density, the
// mixture of the lobes, and draws from it.
class LightLobes {
public:
    LightLobes() = default;  // none: for a vertex that starts no lobe walk
    LightLobes(const RenderScene& scene, const Vec3& p, const SampledWavelengths& w);
    bool empty() const { return mCount == 0; }
    // u picks the lobe, (u1, u2) the direction in it.
    Vec3 sample(float u, float u1, float u2) const;
    float pdf(const Vec3& wi) const;

private:
    static constexpr size_t kMaxLights = 4;
    std::array<Vec3, kMaxLights> mDirs;
    std::array<float, kMaxLights> mShare;  // each lobe's probability
    size_t mCount = 0;
};

}  // namespace mirage
