// How a lamp's intensity varies with the direction it leaves in: the relative intensity
// f(ω) ∈ [0, 1] of a point, spot or sphere light (light/lamp.cpp), and photon directions drawn
// by it. Isotropic (f = 1), a spot's cone (1 inside the inner half-angle, a smoothstep in cos θ
// to 0 at the outer one), or an IES LM-63 distribution (light/ies_file.h) normalised to its
// peak, times the spot's cone when the lamp is a spot.
//
// The lamp's intensity is I(ω) = Φ f(ω) / Ω_f with Ω_f = ∫ f dω, so that it radiates its
// power Φ whatever the profile: a profile shapes where the power goes, it adds none.
#pragma once

#include <memory>

#include "core/distribution.h"
#include "core/math.h"

namespace mirage {

class IesProfile;

// The cone of directions from a lamp that can reach the scene (lamp.cpp's sceneCone): photons
// outside it meet nothing. `valid` false: every direction may.
struct AimCone {
    Vec3 axis;
    float cosMax = -1.f;
    bool valid = false;
};

struct ProfileDesc {
    Vec3 axis{0.f, -1.f, 0.f};  // unit: the spot's direction, an IES file's nadir (γ = 0)
    bool spot = false;
    float innerDeg = 0.f, outerDeg = 180.f;  // the spot's half-angles
    std::shared_ptr<const IesProfile> ies;   // null: no photometric file
};

class EmissionProfile {
public:
    explicit EmissionProfile(const ProfileDesc& desc = {});
    // f(ω) for the unit direction the light travels.
    float eval(const Vec3& w) const {
        const float cosT = dot(w, mAxis);
        const float cone = mSpot ? falloff(cosT) : 1.f;
        return mIes && cone > 0.f ? cone * iesValue(w, cosT) : cone;
    }
    // Ω_f = ∫ f dω (sr): 4π isotropic, 2π(1 − (cos θi + cos θo)/2) for a spot (exact, below),
    // by quadrature over the sphere with an IES file.
    float solidAngle() const { return mSolidAngle; }
    const Vec3& axis() const { return mAxis; }
    bool spot() const { return mSpot; }
    bool photometric() const { return bool(mIes); }
    // The cone outside which f = 0 (cos of its half-angle; −1: none).
    float cosCone() const { return mSpot ? mCosOuter : -1.f; }

    // The share of the power a photon drawn by `sample` stands for: that of the aim cone for an
    // isotropic lamp (whose photons then weigh 1), else 1.
    float aimedShare(const AimCone& aim) const;
    // A direction of travel and its photon weight f / (pdf Ω_f share), mean 1 over the profile.
    // False when the direction carries nothing.
    bool sample(const AimCone& aim, float u1, float u2, Vec3* w, float* weight) const;

private:
    float falloff(float cosT) const {
        if (cosT >= mCosInner) return 1.f;
        if (cosT <= mCosOuter) return 0.f;
        const float t = (cosT - mCosOuter) / (mCosInner - mCosOuter);
        return t * t * (3.f - 2.f * t);
    }
    float iesValue(const Vec3& w, float cosT) const;
    void tabulate();

    Vec3 mAxis;
    Frame mFrame;  // n = axis; s = the IES file's C = 0° plane
    bool mSpot;
    float mCosInner = 1.f, mCosOuter = -1.f;
    float mSolidAngle = 4.f * kPi;
    std::shared_ptr<const IesProfile> mIes;
    // With an IES file: directions drawn over (φ/2π, (1 − cos γ)/2) ∝ f, cell by cell.
    std::shared_ptr<const Distribution2D> mTable;
};

}  // namespace mirage
