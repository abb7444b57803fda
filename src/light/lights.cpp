#include "light/light.h"

#include <cstdio>

#include "core/error.h"

namespace mirage {

Spectrum normalizedPowerSpectrum(const Spectrum& colour) {
    double integral = 0.0;
    for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
        integral += colour(float(l)) * ((l == int(kLambdaMin) || l == int(kLambdaMax)) ? 0.5 : 1.0);
    if (!(integral > 0.0)) throw MirageError("light colour has no energy in 360–830 nm");
    return colour.scaled(float(1.0 / integral));
}

namespace {

std::string vecStr(const Vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%g, %g, %g)", v.x, v.y, v.z);
    return buf;
}

class PointLight : public Light {
public:
    PointLight(const Vec3& p, float power, const Spectrum& c)
        : mP(p), mPower(power), mI(normalizedPowerSpectrum(c).scaled(power * kInv4Pi)) {}
    bool sampleLi(const Vec3& p, float, float, const SampledWavelengths& w,
                  LightSample* out) const override {
        Vec3 d = mP - p;
        float d2 = dot(d, d);
        if (d2 <= 0.f) return false;
        out->distance = std::sqrt(d2);
        out->wi = d / out->distance;
        out->Li = mI.sample(w) / d2;  // I/r²: inverse-square law
        return true;
    }
    std::string describe() const override {
        return "point light at " + vecStr(mP) + ", " + std::to_string(mPower) + " W";
    }

private:
    Vec3 mP;
    float mPower;
    Spectrum mI;  // W/sr/nm
};

class SpotLight : public Light {
public:
    SpotLight(const Vec3& p, const Vec3& dir, float power, float inner, float outer,
              const Spectrum& c)
        : mP(p), mDir(normalize(dir)), mPower(power) {
        outer = clamp(outer, 0.01f, 180.f);
        inner = clamp(inner, 0.f, outer);
        mCosOuter = std::cos(radians(outer));
        mCosInner = std::cos(radians(inner));
        // Solid angle weighted by the falloff, with the smoothstep approximated by the
        // midpoint: Ω ≈ 2π(1 − (cosInner + cosOuter)/2), as in pbrt-v3's spot light.
        float omega = 2.f * kPi * (1.f - 0.5f * (mCosInner + mCosOuter));
        mI = normalizedPowerSpectrum(c).scaled(power / omega);
    }
    bool sampleLi(const Vec3& p, float, float, const SampledWavelengths& w,
                  LightSample* out) const override {
        Vec3 d = mP - p;
        float d2 = dot(d, d);
        if (d2 <= 0.f) return false;
        out->distance = std::sqrt(d2);
        out->wi = d / out->distance;
        float cosT = dot(-out->wi, mDir);
        float f = falloff(cosT);
        if (f <= 0.f) return false;
        out->Li = mI.sample(w) * (f / d2);
        return true;
    }
    std::string describe() const override {
        return "spot light at " + vecStr(mP) + " towards " + vecStr(mDir) + ", " +
               std::to_string(mPower) + " W";
    }

private:
    float falloff(float cosT) const {
        if (cosT >= mCosInner) return 1.f;
        if (cosT <= mCosOuter) return 0.f;
        float t = (cosT - mCosOuter) / (mCosInner - mCosOuter);
        return t * t * (3.f - 2.f * t);
    }
    Vec3 mP, mDir;
    float mPower, mCosInner, mCosOuter;
    Spectrum mI;
};

class DistantLight : public Light {
public:
    DistantLight(const Vec3& dir, float E, const Spectrum& c)
        : mDir(normalize(dir)), mE(E), mSpd(normalizedPowerSpectrum(c).scaled(E)) {}
    bool sampleLi(const Vec3&, float, float, const SampledWavelengths& w,
                  LightSample* out) const override {
        out->wi = -mDir;
        out->distance = kInfinity;
        out->Li = mSpd.sample(w);
        return true;
    }
    std::string describe() const override {
        return "distant light along " + vecStr(mDir) + ", " + std::to_string(mE) + " W/m²";
    }

private:
    Vec3 mDir;
    float mE;
    Spectrum mSpd;  // W/m²/nm
};

class QuadLight : public Light {
public:
    QuadLight(const Vec3& corner, const Vec3& u, const Vec3& v, float power, const Spectrum& c)
        : mCorner(corner), mU(u), mV(v), mPower(power) {
        Vec3 n = cross(u, v);
        mArea = length(n);
        if (!(mArea > 0.f)) throw MirageError("quad light: edges are parallel or zero");
        mN = n / mArea;
        mL = normalizedPowerSpectrum(c).scaled(power / (kPi * mArea));
    }
    bool sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                  LightSample* out) const override {
        // Uniform area sampling; pdf in solid angle = d² / (A cosθ_l).
        Vec3 q = mCorner + mU * u1 + mV * u2;
        Vec3 d = q - p;
        float d2 = dot(d, d);
        if (d2 <= 0.f) return false;
        out->distance = std::sqrt(d2);
        out->wi = d / out->distance;
        float cosL = -dot(out->wi, mN);
        if (cosL <= 0.f) return false;
        out->Li = mL.sample(w) * (cosL * mArea / d2);
        out->distance *= 0.9999f;  // stop shadow rays just short of the emitter
        return true;
    }
    std::string describe() const override {
        return "quad light at " + vecStr(mCorner) + ", " + std::to_string(mArea) + " m², " +
               std::to_string(mPower) + " W";
    }

private:
    Vec3 mCorner, mU, mV, mN;
    float mArea, mPower;
    Spectrum mL;  // W/m²/sr/nm
};

}  // namespace

std::unique_ptr<Light> makePointLight(const Vec3& p, float power, const Spectrum& c) {
    return std::make_unique<PointLight>(p, power, c);
}
std::unique_ptr<Light> makeSpotLight(const Vec3& p, const Vec3& dir, float power, float inner,
                                     float outer, const Spectrum& c) {
    return std::make_unique<SpotLight>(p, dir, power, inner, outer, c);
}
std::unique_ptr<Light> makeDistantLight(const Vec3& dir, float E, const Spectrum& c) {
    return std::make_unique<DistantLight>(dir, E, c);
}
std::unique_ptr<Light> makeQuadLight(const Vec3& corner, const Vec3& u, const Vec3& v,
                                     float power, const Spectrum& c) {
    return std::make_unique<QuadLight>(corner, u, v, power, c);
}

}  // namespace mirage
