// The beam radiance estimate (Jarosz, Zwicker & Jensen 2008, "The Beam Radiance Estimate for
// Volumetric Photon Mapping", eq. 16 with the photon discs of §4.2):
//
//     L_b(x, w) = Σ_i K_i(d_i) T(x, x_i') p(θ_i) Φ_i
//
// summed over every photon i whose disc — centre x_i, radius r_i, facing the ray — the camera
// ray crosses; d_i is the distance from x_i to the ray, x_i' the projection of x_i on it, T the
// transmittance from the camera to x_i', θ_i the angle between the photon's direction and the
// direction towards the camera. It replaces the ray march of point queries by one query per
// ray and integrates the photon density along the ray exactly (no step size). As in
// volume_estimate.h the result is CIE XYZ, each photon at its own wavelength.
//
// Heterogeneous media: each photon is weighted by σs(x_i', λ_i)/σs(x_i, λ_i), the paper's form
// being the uniform case where the ratio is 1. A photon samples the fluence at x_i as
// ΔΦ/σs(x_i) per unit volume; the camera ray in-scatters it at x_i' with its own σs(x_i').
// Without the ratio a disc carries light from dense smoke across its radius into thin smoke,
// empty space or through a glass wall (the point estimate's weight, volume_estimate.h). A
// re-emitted photon is weighted by the ratio of re-emission densities likewise.
//
// Kernel: the photon's flux is spread over its disc by a normalised 2D kernel (∫ K dA = 1).
// Default: the Silverman biweight K(d) = 3/(π r²)(1 − d²/r²)² (Silverman 1986, eq. 4.5), which
// falls smoothly to 0 at the disc edge, so a photon entering or leaving a pixel's footprint
// does not make the blotchy edges of the box kernel 1/(π r²); the price is a narrower
// effective footprint (more noise) at the same r.
//
// Acceleration: Embree 3's ray-facing disc primitive (RTC_GEOMETRY_TYPE_DISC_POINT, per-photon
// radius in the 4th float of each vertex) is exactly the photon disc of the paper; an intersect
// filter records every hit and rejects it, so the traversal goes on and visits every disc the
// ray crosses. Embree builds with curve self-intersection avoidance (the default since 3.12)
// reject points nearer than 2·radius to the ray origin along the ray; the query ray therefore
// starts well behind the camera and only its original span is kept (tested with rays that
// start inside the photon cloud).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "photon/view_weight.h"
#include "photon/volume_estimate.h"

namespace mirage {

enum class BeamKernel { Biweight, Box };

// One photon disc crossed by a ray: slot in the photon map, ray parameter of the photon's
// projection (m), squared distance from the photon to the ray (m²).
struct BeamHit {
    uint32_t slot;
    float t;
    float d2;
};

class BeamEstimator {
public:
    // radii[i] is the disc radius of slot i of photons.map() (PhotonMap::photonRadii). The
    // photons must outlive the estimator.
    BeamEstimator(const VolumePhotons& photons, std::vector<float> radii,
                  BeamKernel kernel = BeamKernel::Biweight);
    ~BeamEstimator();
    BeamEstimator(const BeamEstimator&) = delete;
    BeamEstimator& operator=(const BeamEstimator&) = delete;

    const std::vector<float>& radii() const { return mRadii; }
    BeamKernel kernel() const { return mKernel; }

    // Every photon with d_i ≤ r_i whose projection lies in [tMin, tMax] along `ray` (unit
    // direction), in slot order: deterministic whatever Embree's traversal order. `hits` is
    // cleared first and reused, so a per-thread vector allocates only while it grows.
    void query(const Ray& ray, float tMin, float tMax, std::vector<BeamHit>* hits) const;

    // L_b along `ray` over (0, tMax) as XYZ (W·m⁻²·sr⁻¹·nm⁻¹); `depth` has been marched along
    // the same ray and gives T at each photon's wavelength; `view` weights each photon by what
    // the camera path puts in front of this ray (view_weight.h). σs at the photons' projections
    // is read through a ScatteringProbe of the calling thread, kept by the estimator. `groups`,
    // when active, receives the estimate split by light group (photon_groups.h).
    Vec3 estimate(const Ray& ray, float tMax, const RayOpticalDepth& depth,
                  std::vector<BeamHit>* scratch, const ViewWeight& view = ViewWeight(),
                  const PhotonGroups& groups = PhotonGroups()) const;

    // The 2D kernel at squared distance d2 from the centre of a disc of radius r (1/m²).
    float kernelValue(float d2, float r) const {
        float r2 = r * r;
        if (!(d2 <= r2)) return 0.f;
        if (mKernel == BeamKernel::Box) return kInvPi / r2;
        float s = 1.f - d2 / r2;
        return 3.f * kInvPi / r2 * s * s;
    }

private:
    struct Bvh;
    struct Probes;

    const VolumePhotons* mPhotons;
    std::vector<float> mRadii;
    BeamKernel mKernel;
    std::unique_ptr<Bvh> mBvh;
    std::unique_ptr<Probes> mProbes;
};

}  // namespace mirage
