// Where the light is, for paths in strongly forward media (sea water's particles, HG g 0.92:
// p(0) = 26/sr against a mean of 1/4π): lobes about the directions towards the lights, which
// the path tracer's lobe walks draw from (render/lobe_walk.h).
//
// Why. A medium vertex's next-event estimate scores p(θ) of the angle between the path's last
// segment and the light. In such a medium the light seen just past the forward lobe — an
// aureole about a lamp, a glow about the sun's beam — is bright and narrow, and a path finds it
// only when its phase or cosine sample happens to point at the light: rare, bright samples,
// the speckles of the Cornell-water and underwater scenes. Drawing directions from lobes about
// the lights finds it at the lobes' density.
// Not used (plain sampling, the same random numbers as before) where no medium of the scene
// peaks above 5/sr (HG g ≳ 0.82): smoke, fog and clouds keep their paths.
//
// Lamps inside smoke and fog (lampsInMedia) have lobes of another shape, which volpath's medium
// vertices draw a share of their continuations from (volpath.cpp, "Lobes towards lamps"): the
// angle θ to the lamp uniform on [0, π/2] (core/sampling.h: sampleUniformAngle), a density
// ∝ 1/θ. Why. The segment after a vertex at a distance r from a lamp passes it at D = r sin θ,
// and the lamp's equiangular point on that segment (render/lamp_sampling.h) estimates its
// single scattering as ∝ (θb − θa)/D: bounded for the segment, but the phase function's
// directions pass within D with a probability ∝ D², so the estimate's second moment,
// ∫ D⁻² D dD, diverges as log D: the fireflies of a dark pixel whose paths wander past the lamp
// after a bounce. Drawn ∝ 1/θ, the probability is ∝ D and p/pdf ∝ sin θ cancels the 1/D. Each
// lamp is chosen in proportion to Φ/r (its power over its distance), which minimises the sum
// over lamps of that estimate's second moment, Σ Φ² / (share r²), for a given sum of shares.
#pragma once

#include <array>
#include <vector>

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

// A point, spot or sphere light whose light scatters off a medium right about it: its
// position (a sphere's centre) and power (W).
struct MediumLamp {
    Vec3 p;
    float power = 0.f;
};

// The lamps whose lobes volpath's continuations draw from: the scene's lamps inside or near a
// medium, those with a majorant cell of some medium within one cell (and a sphere light's
// radius) of their position, the four most powerful. Empty where no lamp sits where its light
// scatters close by (a spot outside a ball of haze, a lamp in the empty corner of a cache's box),
// where paths draw no equiangular points towards lamps ([render] lamp_sampling = "distance",
// RenderScene::equiangular: their 1/D estimates are what the lobes bound) and where lobe walks
// guide the paths (guidesPaths): then no path draws them.
std::vector<MediumLamp> lampsInMedia(const RenderScene& scene);

// The probability that a continuation from a medium vertex is drawn from the lamps' lobes
// rather than the phase function (volpath.cpp, "Lobes towards lamps").
constexpr float kLampLobeShare = 0.4f;

// Lobes about the directions from a point towards lights: each chosen with a share, the guide's
// density the mixture of the lobes, and draws from it.
// - Forward (the constructor): HG g 0.9 about every light not at infinity (at most four; a
//   distant light's direction, a point's, about a quad's middle), each chosen in proportion to
//   the light that would arrive unblocked (its sample's mean Li/pdf at (½, ½)), so that a lamp in
//   the next room of a scene draws few directions.
// - Lamp (towardsLamps): the angle to the lamp uniform on [0, π/2], each lamp in proportion to
//   Φ/r (above).
class LightLobes {
public:
    LightLobes() = default;  // none: for a vertex that starts no lobe walk
    LightLobes(const RenderScene& scene, const Vec3& p, const SampledWavelengths& w);
    static LightLobes towardsLamps(const std::vector<MediumLamp>& lamps, const Vec3& p);
    bool empty() const { return mCount == 0; }
    // u picks the lobe, (u1, u2) the direction in it.
    Vec3 sample(float u, float u1, float u2) const;
    float pdf(const Vec3& wi) const;

private:
    enum class Shape { Forward, Lamp };
    Shape mShape = Shape::Forward;
    static constexpr size_t kMaxLights = 4;
    std::array<Vec3, kMaxLights> mDirs;
    std::array<float, kMaxLights> mShare;  // each lobe's probability
    size_t mCount = 0;
    void add(const Vec3& dir, float weight);  // a lobe of that weight (> 0) before normalising
    void normalise();
};

}  // namespace mirage
