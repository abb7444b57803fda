// Point, spot and sphere lights: a lamp at a point, or a sphere of radius r about it, whose
// intensity by direction is its profile's (light/emission_profile.h): I(ω) = Φ f(ω) / Ω_f.
//
// A sphere light's surface sends the radiance L(ω) = I(ω) / (π r²) along ω from every point
// of its outer side that faces ω. Seen from afar along ω it covers the disc π r², so its
// intensity is I(ω) — the point light's — and its power Φ; from a point p at distance d > r it
// fills the cone of half-angle θmax, sin θmax = r/d, with the constant radiance L(−wi) over
// the directions wi that meet it. The irradiance on a surface facing an isotropic sphere is
// then π L sin²θmax = Φ / (4π d²), the point light's exactly (the sphere's field outside it
// is that of a point at its centre, as in Newton's shell theorem). As r → 0 the sphere is the
// point light. Inside the sphere (d ≤ r) a point receives nothing: its surface emits outwards.
//
// A sphere's LightSample::pdf stays 0, as a point's: its next-event estimate is not weighed
// against phase-function samples that hit it but against the distances drawn towards its
// centre (render/lamp_sampling.h), which a sphere small in the medium's view needs far more.
#include "light/lamp.h"

#include <algorithm>

#include "core/sampling.h"
#include "light/light_common.h"
#include "spectrum/spectrum_sampling.h"

namespace mirage {

namespace {

// The cone of directions from a lamp at p of radius r that can reach anything inside a sphere
// (centre c, radius R): the scene's bounding sphere (sceneCone), or a specular object's. Seen
// from outside the sphere (at distance d > R + r) a ray from the lamp's surface along ω meets
// it only when the line through p along ω passes within R + r of c, so the cone has half-angle
// asin((R + r)/d) about c − p. A photon leaving outside the scene's cone meets nothing, so
// lamps draw theirs inside (a projection map of one cell: Jensen 2001, §5.1.3). From inside,
// or for empty bounds, there is none (`valid` false) and the lamp emits over all its directions.
// Like the distant light's disc, the cone is straight-line geometry: in a refractive-index field,
// light bent in from outside it is not emitted. The same cone about a specular object's sphere is
// one cell of the lamp's projection map (LampProjection, below).
AimCone coneTowards(const Vec3& p, float lampRadius, const Vec3& centre, float radius) {
    AimCone cone;
    const Vec3 toCentre = centre - p;
    const float d = length(toCentre), r = radius + lampRadius;
    // A margin of 0.1 % keeps a light on the sphere from a degenerate, razor-thin cone.
    if (!(d > 1.001f * r) || !std::isfinite(d)) return cone;
    cone.axis = toCentre / d;
    cone.cosMax = std::sqrt((d - r) * (d + r)) / d;
    cone.valid = true;
    return cone;
}

AimCone sceneCone(const Vec3& p, float lampRadius, const Bounds3& b) {
    if (b.empty()) return AimCone{};
    return coneTowards(p, lampRadius, b.center(), 0.5f * length(b.diagonal()));
}

class LampLight : public Lamp {
public:
    LampLight(const LampDesc& d, const Spectrum& c)
        : mP(d.position),
          mR(d.radius),
          mPower(d.powerW),
          mProfile(d.profile),
          mI(normalizedPowerSpectrum(c).scaled(d.powerW / mProfile.solidAngle())),
          mLambda(normalizedPowerSpectrum(c)) {}

    bool sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                  LightSample* out) const override {
        float scale;  // Li / I(wi) per unit f: 1/d² for a point, Ω L / I for a sphere
        if (!(mR > 0.f ? towardsSphere(p, u1, u2, out, &scale) : towardsPoint(p, out, &scale)))
            return false;
        const float f = mProfile.eval(-out->wi);  // the light leaves along −wi
        if (!(f > 0.f)) return false;
        out->Li = mI.sample(w) * (f * scale);
        return true;
    }
    // The power into the scene: all of it, or an isotropic lamp's share in the aim cone.
    float emittedPower(const Bounds3& b) const override {
        return mPower * mProfile.aimedShare(sceneCone(mP, mR, b));
    }
    // A direction by the profile (weight: its falloff, for spots and IES profiles), then, for a
    // sphere, the point it leaves from: the flux along ω crosses the disc of radius r normal to
    // ω uniformly (constant radiance over the projected area), lifted to the sphere's side
    // facing ω.
    bool emitPhoton(const Bounds3& b, Sampler& s, PhotonEmission* out) const override {
        const float u1 = s.get1D(), u2 = s.get1D();
        const bool lit =
            mProfile.sample(sceneCone(mP, mR, b), u1, u2, &out->direction, &out->weight);
        leave(s, out);
        return mPower > 0.f && lit;
    }
    std::unique_ptr<PhotonProjection> projection(const ProjectionTargets& t) const override;
    std::string describe() const override {
        const char* kind = mProfile.spot() ? "spot" : "point";
        std::string s = std::string(mR > 0.f ? "sphere " : "") + kind + " light at " + vecStr(mP);
        if (mR > 0.f) s += ", radius " + numStr(mR) + " m";
        if (mProfile.spot()) s += " towards " + vecStr(mProfile.axis());
        if (mProfile.photometric()) s += ", IES profile";
        return s + ", " + numStr(mPower) + " W";
    }

    const Spectrum* spectrum() const override { return &mI; }
    std::optional<LightOrigin> origin() const override {
        return LightOrigin{mP, mProfile.axis(), mProfile.cosCone()};
    }
    float radius() const override { return mR; }
    // The spot's cone holds every point it lights from its centre; a sphere's reaches further:
    // the cone tangent to the sphere, its apex r / sin θo behind the centre, holds the sphere
    // and every ray leaving it within θo of the axis (for θo < 90°).
    Vec3 coneApex() const override {
        const float cosO = mProfile.cosCone();
        if (!(mR > 0.f && cosO > 0.f)) return mP;
        return mP - mProfile.axis() * (mR / safeSqrt(1.f - cosO * cosO));
    }

    // The origin of a photon leaving along out->direction, and its wavelength: the centre, or
    // for a sphere a point where the flux along ω crosses the disc of radius r normal to ω
    // uniformly (constant radiance over the projected area), lifted to the side facing ω.
    void leave(Sampler& s, PhotonEmission* out) const {
        out->origin = mP;
        if (mR > 0.f) {
            const float u3 = s.get1D(), u4 = s.get1D();
            const float rho = mR * std::sqrt(u3), phi = 2.f * kPi * u4;
            const Frame f(out->direction);
            out->origin = mP + f.s * (rho * std::cos(phi)) + f.t * (rho * std::sin(phi)) +
                          out->direction * safeSqrt(mR * mR - rho * rho);
        }
        out->lambda = mLambda.sample(s.get1D());
    }
    float power() const { return mPower; }
    const EmissionProfile& profile() const { return mProfile; }
    // The cell of the projection map that holds a target's sphere: the cone of directions that
    // can reach it (coneTowards; every direction from inside it), narrowed to a spot's own cone
    // where that is narrower, since the light outside either reaches nothing of the target.
    // False where the spot's cone and the target's do not meet.
    bool targetCone(const TargetSphere& t, Vec3* axis, float* cosMax) const {
        const AimCone aim = coneTowards(mP, mR, t.centre, t.radius);
        const float cosO = mProfile.cosCone();
        if (!aim.valid) {
            *axis = mProfile.axis();
            *cosMax = cosO;
            return true;
        }
        // Disjoint when the axes lie further apart than the two half-angles together.
        const float apart = std::acos(clamp(dot(aim.axis, mProfile.axis()), -1.f, 1.f));
        if (apart > std::acos(aim.cosMax) + std::acos(cosO)) return false;
        const bool spotNarrower = cosO > aim.cosMax;
        *axis = spotNarrower ? mProfile.axis() : aim.axis;
        *cosMax = spotNarrower ? cosO : aim.cosMax;
        return true;
    }

private:
    // Direction and distance from p to the centre; false when they coincide (the
    // inverse-square law has no finite value there).
    bool towardsPoint(const Vec3& p, LightSample* out, float* scale) const {
        const Vec3 d = mP - p;
        const float d2 = dot(d, d);
        if (!(d2 > 0.f)) return false;
        out->distance = std::sqrt(d2);
        out->wi = d / out->distance;
        *scale = 1.f / d2;  // I/d²: inverse-square law
        return true;
    }
    // A direction uniform in the cone the sphere subtends at p, pdf 1 / (2π(1 − cos θmax)),
    // and the distance to the sphere along it: Li = L / pdf = I 2π(1 − cos θmax) / (π r²).
    // 1 − cos θmax = sin²θmax / (1 + cos θmax), which keeps its precision for a small sphere.
    bool towardsSphere(const Vec3& p, float u1, float u2, LightSample* out, float* scale) const {
        const Vec3 toC = mP - p;
        const float d2 = dot(toC, toC), r2 = mR * mR;
        if (!(d2 > r2)) return false;  // inside: the surface emits outwards
        const float d = std::sqrt(d2), sin2 = r2 / d2, cosMax = safeSqrt(1.f - sin2);
        const float oneMinusCos = sin2 / (1.f + cosMax);
        out->wi = sampleUniformCone(toC / d, cosMax, u1, u2);
        const float b = dot(toC, out->wi);
        out->distance = std::max(0.f, b - safeSqrt(r2 - (d2 - b * b)));
        *scale = 2.f * oneMinusCos / r2;
        return true;
    }

    Vec3 mP;
    float mR, mPower;
    EmissionProfile mProfile;
    Spectrum mI;  // W/sr/nm per unit f
    SpectrumSampler mLambda;
};

// A lamp's projection map: the union of its targets' cones (LampLight::targetCone). A photon
// drawn from the union's mixture, density c(ω)/Σ Ω_k (projection.h), carries the intensity
// I(ω) = Φ f(ω)/Ω_f over that density; normalised by power() = Φ Σ Ω_k / Ω_f, its weight is
// f(ω)/c(ω) ≤ 1.
class LampProjection : public PhotonProjection {
public:
    LampProjection(const LampLight& lamp, ConeUnion cones)
        : mLamp(lamp), mCones(std::move(cones)) {}
    double power() const override {
        return double(mLamp.power()) * mCones.solidAngleSum() / mLamp.profile().solidAngle();
    }
    bool emit(Sampler& s, PhotonEmission* out) const override {
        const float pick = s.get1D(), u1 = s.get1D(), u2 = s.get1D();
        int coverage;
        out->direction = mCones.sample(pick, u1, u2, &coverage);
        out->weight = mLamp.profile().eval(out->direction) / float(coverage);
        mLamp.leave(s, out);
        return out->weight > 0.f;
    }

private:
    const LampLight& mLamp;
    ConeUnion mCones;
};

std::unique_ptr<PhotonProjection> LampLight::projection(const ProjectionTargets& t) const {
    ConeUnion cones;
    for (const TargetSphere& target : t.spheres) {
        Vec3 axis;
        float cosMax;
        if (targetCone(target, &axis, &cosMax)) cones.add(axis, cosMax);
    }
    if (cones.empty() || !(mPower > 0.f)) return nullptr;
    return std::make_unique<LampProjection>(*this, std::move(cones));
}

}  // namespace

std::unique_ptr<Light> makeLamp(const LampDesc& desc, const Spectrum& colour) {
    return std::make_unique<LampLight>(desc, colour);
}

std::unique_ptr<Light> makePointLight(const Vec3& p, float power, const Spectrum& c) {
    LampDesc d;
    d.position = p;
    d.powerW = power;
    return makeLamp(d, c);
}

std::unique_ptr<Light> makeSpotLight(const Vec3& p, const Vec3& dir, float power, float inner,
                                     float outer, const Spectrum& c) {
    LampDesc d;
    d.position = p;
    d.powerW = power;
    d.profile.axis = normalize(dir);
    d.profile.spot = true;
    d.profile.innerDeg = inner;
    d.profile.outerDeg = outer;
    return makeLamp(d, c);
}

}  // namespace mirage
