// Surface photons and the surface radiance estimate (Jensen 2001, §7.1; Jensen & Christensen
// 1998 for the split into caustic and global maps).
//
// At a diffuse surface point x with normal n, seen along wo, the reflected radiance of the
// light the photons carry is estimated from the k nearest photons:
//     L_r(x, wo) ≈ (k − 1)/k · Σ_p f(λ_p) ΔΦ_p / (π r²),   f = ρ(λ_p)/π (Lambertian),
// r the distance to the k-th nearest photon (or maxRadius, without (k − 1)/k, when fewer lie
// within it): the disc kernel of the paper on the tangent plane. The factor (k − 1)/k makes
// the estimate unbiased for a uniform density, as in volume_estimate.h (E[1/A_k] = ρ/(k − 1)
// for the area A_k of the disc through the k-th photon).
// Only photons that arrived on wo's side of the surface (dot(wi_p, n_wo) < 0) and lie within
// r/4 of the tangent plane count: the first keeps light on the other side of a thin wall out,
// the second the photons of an adjacent wall in a corner (which darkens corners slightly, the
// classic bias of this estimate). Output is CIE XYZ (see volume_estimate.h for the units).
#pragma once

#include "geometry/material.h"
#include "photon/photon_groups.h"
#include "photon/photon_map.h"

namespace mirage {

class SurfacePhotons {
public:
    SurfacePhotons() = default;
    explicit SurfacePhotons(PhotonList photons);

    const PhotonMap& map() const { return mMap; }
    size_t size() const { return mMap.size(); }
    bool empty() const { return mMap.empty(); }
    const Vec3& fluxXyz(size_t slot) const { return mFluxXyz[slot]; }

    // L_r at x towards wo (XYZ, W·m⁻²·sr⁻¹·nm⁻¹), each photon's term multiplied by
    // transmittance(λ_p) (the camera segment's attenuation at the photon's wavelength).
    // `ng` is the geometric normal; `buffer` holds k entries, k ≥ 2. `groups`, when active,
    // receives the estimate split by light group (photon_groups.h).
    template <typename T>
    Vec3 estimate(const Vec3& x, const Vec3& ng, const Vec3& wo, const Material& material, int k,
                  float maxRadius, PhotonNeighbour* buffer, T&& transmittance,
                  const PhotonGroups& groups = PhotonGroups()) const;

private:
    PhotonMap mMap;
    std::vector<Vec3> mFluxXyz;
};

template <typename T>
Vec3 SurfacePhotons::estimate(const Vec3& x, const Vec3& ng, const Vec3& wo,
                              const Material& material, int k, float maxRadius,
                              PhotonNeighbour* buffer, T&& transmittance,
                              const PhotonGroups& groups) const {
    if (mMap.empty() || material.specular()) return Vec3(0.f);
    int found = mMap.nearest(x, k, maxRadius, buffer);
    if (found == 0) return Vec3(0.f);
    const Vec3 n = dot(wo, ng) >= 0.f ? ng : -ng;
    const float r2 = found == k ? buffer[0].d2 : maxRadius * maxRadius;
    if (!(r2 > 0.f)) return Vec3(0.f);
    const float planeTolerance = 0.25f * std::sqrt(r2);
    const float scale = (found == k ? float(k - 1) / float(k) : 1.f) / (kPi * r2);
    const PhotonGroups scaledGroups = groups.scaled(scale);
    Vec3 sum(0.f);
    for (int i = 0; i < found; ++i) {
        const Photon& ph = mMap[buffer[i].index];
        if (dot(ph.wi, n) >= 0.f) continue;
        if (std::abs(dot(ph.p - x, n)) > planeTolerance) continue;
        float f = material.albedo(ph.lambda) * kInvPi;
        const Vec3 term = fluxXyz(buffer[i].index) * (f * transmittance(ph.lambda));
        sum += term;
        scaledGroups.add(ph, term);
    }
    return sum * scale;
}

}  // namespace mirage
