// Distant and quad lights (point, spot and sphere lights are light/lamp.cpp): incident-light
// sampling for the render pass, photon emission for the photon pass. Emission sampling
// (origin, direction) is exact; wavelengths come from a SpectrumSampler over the normalised
// spectral power distribution.
#include <cstdio>

#include "core/error.h"
#include "core/sampling.h"
#include "core/surface_epsilon.h"
#include "light/light.h"
#include "light/light_common.h"
#include "light/spherical_rectangle.h"
#include "spectrum/spectrum_sampling.h"

namespace mirage {

double powerIntegral(const Spectrum& s) {
    double integral = 0.0;
    for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
        integral += s(float(l)) * ((l == int(kLambdaMin) || l == int(kLambdaMax)) ? 0.5 : 1.0);
    return integral;
}

Spectrum normalizedPowerSpectrum(const Spectrum& colour) {
    const double integral = powerIntegral(colour);
    if (!(integral > 0.0)) throw MirageError("light colour has no energy in 360–830 nm");
    return colour.scaled(float(1.0 / integral));
}

std::string vecStr(const Vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v.x, v.y, v.z);
    return buf;
}

std::string numStr(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

namespace {

class DistantLight : public Light {
public:
    DistantLight(const Vec3& dir, float E, const Spectrum& c)
        : mDir(normalize(dir)),
          mE(E),
          mSpd(normalizedPowerSpectrum(c).scaled(E)),
          mLambda(normalizedPowerSpectrum(c)) {}
    bool sampleLi(const Vec3&, float, float, const SampledWavelengths& w,
                  LightSample* out) const override {
        out->wi = -mDir;
        out->distance = kInfinity;
        out->Li = mSpd.sample(w);
        return true;
    }
    // The light crosses the scene through the disc of radius r (the bounding sphere's) normal
    // to its direction: E π r² watts. A bounding sphere rather than the box's exact shadow
    // keeps the disc round and easy to sample whatever the direction; the photons that miss
    // the box (58 % for a cube of side a seen along an axis: shadow a², disc 3πa²/4) fly out
    // at the cost of a box test, and a sun over a small cache still aims every photon at it.
    float emittedPower(const Bounds3& b) const override {
        if (b.empty()) return 0.f;
        float r = 0.5f * length(b.diagonal());
        return mE * kPi * r * r;
    }
    // Uniform point on that disc, placed upstream of the sphere (just outside it, so that the
    // photon starts outside every medium), travelling along the light's direction.
    bool emitPhoton(const Bounds3& b, Sampler& s, PhotonEmission* out) const override {
        if (b.empty()) return false;
        float r = 0.5f * length(b.diagonal());
        float u1 = s.get1D(), u2 = s.get1D();
        float rho = r * std::sqrt(u1), phi = 2.f * kPi * u2;
        Frame f(mDir);
        out->origin = b.center() + f.s * (rho * std::cos(phi)) + f.t * (rho * std::sin(phi)) -
                      mDir * (r * 1.001f);
        out->direction = mDir;
        out->lambda = mLambda.sample(s.get1D());
        out->weight = 1.f;
        return mE > 0.f && r > 0.f;
    }
    std::unique_ptr<PhotonProjection> projection(const ProjectionTargets& t) const override;
    std::string describe() const override {
        return "distant light along " + vecStr(mDir) + ", " + numStr(mE) + " W/m²";
    }
    float irradiance() const { return mE; }
    const Vec3& direction() const { return mDir; }
    float sampleLambda(float u) const { return mLambda.sample(u); }

    const Spectrum* spectrum() const override { return &mSpd; }

private:
    Vec3 mDir;
    float mE;
    Spectrum mSpd;  // W/m²/nm
    SpectrumSampler mLambda;
};

// The distant light's projection map: the targets' discs facing its direction (DiscUnion), each
// a uniform point of the union's mixture (density c/Σ πR_k²) started upstream of the scene,
// so that power() = E Σ πR_k² and the weight is 1/c.
class DistantProjection : public PhotonProjection {
public:
    DistantProjection(const DistantLight& light, const ProjectionTargets& t)
        : mLight(light), mDiscs(t.spheres), mScene(t.scene) {}
    double power() const override { return double(mLight.irradiance()) * mDiscs.areaSum(); }
    bool emit(Sampler& s, PhotonEmission* out) const override {
        const float pick = s.get1D(), u1 = s.get1D(), u2 = s.get1D();
        int coverage;
        out->direction = mLight.direction();
        out->origin = upstreamOfScene(
            mScene, mDiscs.sample(out->direction, pick, u1, u2, &coverage), out->direction);
        out->lambda = mLight.sampleLambda(s.get1D());
        out->weight = 1.f / float(coverage);
        return true;
    }

private:
    const DistantLight& mLight;
    DiscUnion mDiscs;
    Bounds3 mScene;
};

std::unique_ptr<PhotonProjection> DistantLight::projection(const ProjectionTargets& t) const {
    if (t.spheres.empty() || t.scene.empty() || !(mE > 0.f)) return nullptr;
    return std::make_unique<DistantProjection>(*this, t);
}

class QuadLight : public Light {
public:
    QuadLight(const Vec3& corner, const Vec3& u, const Vec3& v, float power, const Spectrum& c)
        : mCorner(corner), mU(u), mV(v), mPower(power) {
        Vec3 n = cross(u, v);
        mArea = length(n);
        if (!(mArea > 0.f)) throw MirageError("quad light: edges are parallel or zero");
        mN = n / mArea;
        mL = normalizedPowerSpectrum(c).scaled(power / (kPi * mArea));
        mLambda = SpectrumSampler(normalizedPowerSpectrum(c));
    }
    // A rectangle seen from p is sampled uniformly in solid angle (light/spherical_rectangle.h):
    // Li = L Ω, bounded near the light. A parallelogram, or a rectangle too small in p's sky
    // for Ω to be resolved, uniformly over its area: pdf in solid angle d² / (A cosθ_l).
    bool sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                  LightSample* out) const override {
        if (dot(p - mCorner, mN) <= 0.f) return false;  // behind the one-sided emitter
        SphericalRectangle rect;
        const bool solidAngle = bySolidAngle(p, &rect);
        const Vec3 q = solidAngle ? rect.sample(u1, u2) : mCorner + mU * u1 + mV * u2;
        if (!towards(p, q, out)) return false;
        out->pdf = solidAngle ? float(1.0 / rect.solidAngle()) : areaPdf(*out);
        out->Li = mL.sample(w) / out->pdf;
        out->distance *= 0.9999f;  // stop shadow rays just short of the emitter
        return true;
    }
    bool hitLi(const Vec3& p, const Vec3& wi, const SampledWavelengths& w,
               LightSample* out) const override {
        const float facing = -dot(wi, mN), height = dot(p - mCorner, mN);
        if (!(facing > 0.f && height > 0.f)) return false;
        const Vec3 q = p + wi * (height / facing);
        // Coordinates of q along the edges (dual basis: the quad may be a parallelogram).
        const Vec3 cu = cross(mV, mN), cv = cross(mN, mU);
        const float a = dot(q - mCorner, cu) / dot(mU, cu), b = dot(q - mCorner, cv) / dot(mV, cv);
        if (!(a >= 0.f && a <= 1.f && b >= 0.f && b <= 1.f)) return false;
        if (!towards(p, q, out)) return false;
        SphericalRectangle rect;
        out->pdf = bySolidAngle(p, &rect) ? float(1.0 / rect.solidAngle()) : areaPdf(*out);
        out->Li = mL.sample(w);
        out->distance *= 0.9999f;
        return true;
    }
    float emittedPower(const Bounds3&) const override { return mPower; }
    // Constant radiance: the origin is uniform over the area, the direction cosine-weighted
    // about the normal (dΦ = L cosθ dA dω), so the photon weight is exactly 1. The origin is
    // pushed off the quad to its emitting side, as a ray spawned at a surface is: a light
    // lying on a ceiling would otherwise send photons that hit the ceiling at t ≈ 0.
    bool emitPhoton(const Bounds3&, Sampler& s, PhotonEmission* out) const override {
        float u1 = s.get1D(), u2 = s.get1D();
        const Vec3 q = mCorner + mU * u1 + mV * u2;
        out->origin = q + mN * surfaceEpsilon(q);
        float u3 = s.get1D(), u4 = s.get1D();
        // Lambertian: the radiance is constant, so the flux leaves ∝ cos θ about the normal.
        out->direction = Frame(mN).toWorld(sampleCosineHemispherePolar(u3, u4));
        out->lambda = mLambda.sample(s.get1D());
        out->weight = 1.f;
        return mPower > 0.f;
    }
    std::string describe() const override {
        return "quad light at " + vecStr(mCorner) + ", " + numStr(mArea) + " m², " +
               numStr(mPower) + " W";
    }

    const Spectrum* spectrum() const override { return &mL; }

private:
    bool bySolidAngle(const Vec3& p, SphericalRectangle* rect) const {
        return rect->setup(p, mCorner, mU, mV) && rect->solidAngle() > 1e-4;
    }
    // Direction and distance from p to the point q on the quad; false from behind or on it.
    bool towards(const Vec3& p, const Vec3& q, LightSample* out) const {
        const Vec3 d = q - p;
        const float d2 = dot(d, d);
        if (!(d2 > 0.f)) return false;
        out->distance = std::sqrt(d2);
        out->wi = d / out->distance;
        return -dot(out->wi, mN) > 0.f;
    }
    // Solid-angle pdf of a point drawn uniformly over the area: d² / (A cosθ_l).
    float areaPdf(const LightSample& s) const {
        return s.distance * s.distance / (mArea * -dot(s.wi, mN));
    }

    Vec3 mCorner, mU, mV, mN;
    float mArea, mPower;
    Spectrum mL;  // W/m²/sr/nm
    SpectrumSampler mLambda;
};

}  // namespace

std::unique_ptr<Light> makeDistantLight(const Vec3& dir, float E, const Spectrum& c) {
    return std::make_unique<DistantLight>(dir, E, c);
}
std::unique_ptr<Light> makeQuadLight(const Vec3& corner, const Vec3& u, const Vec3& v, float power,
                                     const Spectrum& c) {
    return std::make_unique<QuadLight>(corner, u, v, power, c);
}

}  // namespace mirage
