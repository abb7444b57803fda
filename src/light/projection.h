// Projection maps (Jensen 2001, Realistic Image Synthesis Using Photon Mapping, §5.1.3): the
// directions (a lamp) or the patch of the incoming wavefront (a light at infinity) through
// which a light reaches the scene's specular objects, so that caustic photons are emitted only
// there. Jensen marks cells of a direction map that hold specular geometry; here each specular
// object is its bounding sphere, whose cone (seen from a lamp) or disc (seen along a parallel
// beam) is exact and cheap, and the projection is the union of them.
//
// A union is sampled as a mixture: target k with probability ∝ its measure m_k (solid angle or
// area), then uniformly inside it. The density at a point x of the union is c(x) / Σ m_k, with
// c(x) the number of targets holding x, so a photon drawn there carries the light's emission
// over that density: overlaps are not counted twice, and the estimate stays unbiased however
// the spheres overlap. Σ m_k is what the union's photons stand for at the light's full
// emission; the lights scale it by their own (light.h, Light::projection).
#pragma once

#include <memory>
#include <vector>

#include "core/math.h"
#include "core/rng.h"

namespace mirage {

struct PhotonEmission;

// A specular object as the projection sees it: a sphere holding it (world metres).
struct TargetSphere {
    Vec3 centre;
    float radius = 0.f;
};

// What a light builds its projection from: the specular objects, and the scene's bounds (a
// light at infinity starts its photons upstream of them, outside every medium).
struct ProjectionTargets {
    std::vector<TargetSphere> spheres;
    Bounds3 scene;
};

// A light's projection map: the caustic photons it emits and the power they stand for.
class PhotonProjection {
public:
    virtual ~PhotonProjection() = default;
    // W: the normalisation of the projection's photons: a photon of weight w (PhotonEmission)
    // carries power() / N × w when it is one of N drawn from it. At least the power the light
    // sends into the union (the lights take Σ m_k at their peak emission).
    virtual double power() const = 0;
    // A photon into the union, its weight the emission over the mixture's density (mean: the
    // share of power() the union receives). False when it carries nothing.
    virtual bool emit(Sampler& sampler, PhotonEmission* out) const = 0;
};

// Cones of directions from one point, each given by its unit axis and the cosine of its
// half-angle (−1: every direction).
class ConeUnion {
public:
    void add(const Vec3& axis, float cosMax);
    bool empty() const { return mCones.empty(); }
    // Σ Ω_k (sr), Ω_k = 2π(1 − cos θ_k): each overlap counted as often as it is covered.
    double solidAngleSum() const { return mTotal; }
    // Cone k ∝ Ω_k (by uPick), then uniform in it; *coverage = the cones holding the direction
    // (≥ 1: the drawn one holds it even where rounding puts it on another's edge).
    Vec3 sample(float uPick, float u1, float u2, int* coverage) const;
    // The mixture's density at the unit direction w (1/sr): cones holding w over Σ Ω_k.
    double pdf(const Vec3& w) const;

private:
    struct Cone {
        Vec3 axis;
        float cosMax;
    };
    size_t pick(float u) const;
    int holding(const Vec3& w, size_t except) const;

    std::vector<Cone> mCones;
    std::vector<double> mCdf;  // Σ Ω up to and including each cone
    double mTotal = 0.0;
};

// Discs facing a parallel beam: each target sphere's cross-section normal to the beam's
// direction d, wherever the beam comes from (the distant light's d is fixed, the dome's drawn
// per photon).
class DiscUnion {
public:
    explicit DiscUnion(std::vector<TargetSphere> spheres);
    bool empty() const { return mSpheres.empty(); }
    // Σ π R_k² (m²).
    double areaSum() const { return mTotal; }
    // A point of the union in the plane through the drawn disc's centre normal to d (unit), by
    // disc k ∝ R_k² (uPick) then uniform on it; *coverage as ConeUnion::sample.
    Vec3 sample(const Vec3& d, float uPick, float u1, float u2, int* coverage) const;
    // The mixture's density (1/m²) at the beam line through p along d: discs it crosses over
    // Σ π R_k².
    double pdf(const Vec3& d, const Vec3& p) const;

private:
    size_t pick(float u) const;
    int holding(const Vec3& d, const Vec3& p, size_t except) const;

    std::vector<TargetSphere> mSpheres;
    std::vector<double> mCdf;
    double mTotal = 0.0;
};

// Where a photon travelling along the unit direction d through the point p starts: on the line,
// just upstream of the scene's bounding sphere, so that it starts outside every medium (as a
// distant light's photons do).
Vec3 upstreamOfScene(const Bounds3& scene, const Vec3& p, const Vec3& d);

}  // namespace mirage
