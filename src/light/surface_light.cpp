// Emissive triangles as a light (surface_light.h).
#include "light/surface_light.h"

#include "core/sampling.h"
#include "core/surface_epsilon.h"
#include "light/light_common.h"

namespace mirage {

namespace {

// Twice the triangle's area vector (a, b, c counter-clockwise: along its normal).
Vec3 areaVector(const Vec3& a, const Vec3& b, const Vec3& c) { return cross(b - a, c - a); }

}  // namespace

SurfaceLight::SurfaceLight(EmissiveTriangles t) : mTris(std::move(t)) {
    MIRAGE_CHECK(mTris.vertices.size() == 3 * mTris.emitter.size());
    for (const Spectrum& L : mTris.radiance) {
        mEmitterPower.push_back(powerIntegral(L));
        mLambda.push_back(mEmitterPower.back() > 0.0
                              ? std::make_shared<const SpectrumSampler>(normalizedPowerSpectrum(L))
                              : nullptr);
    }
    std::vector<double> weights(triangleCount());
    for (size_t k = 0; k < triangleCount(); ++k) {
        const Vec3* v = &mTris.vertices[3 * k];
        const double area = 0.5 * double(length(areaVector(v[0], v[1], v[2])));
        weights[k] = std::isfinite(area) ? area * mEmitterPower[size_t(mTris.emitter[k])] : 0.0;
        mWeightSum += weights[k];
    }
    for (size_t m = 0; m < mEmitterPower.size(); ++m)
        if (mEmitterPower[m] > 0.0) mOnly = mOnly == -1 ? int(m) : -2;
    mOnly = std::max(mOnly, -1);
    mChoice = Distribution1D(std::move(weights));
    mPower = float(2.0 * kPi * mWeightSum);
}

// The triangle for u, and u made uniform again within the triangle's share of [0, 1).
size_t SurfaceLight::chooseTriangle(float* u) const {
    size_t k;
    const float x = mChoice.sample(*u, &k);
    *u = clamp(x * float(triangleCount()) - float(k), 0.f, 0x1.fffffep-1f);
    return k;
}

Vec3 SurfaceLight::pointOn(size_t k, float u1, float u2, Vec3* n) const {
    const Vec3* v = &mTris.vertices[3 * k];
    *n = normalize(areaVector(v[0], v[1], v[2]));
    const float s = std::sqrt(u1);
    return v[0] * (1.f - s) + v[1] * (s * (1.f - u2)) + v[2] * (s * u2);
}

float SurfaceLight::pdfAt(int emitter, const Vec3& p, const Vec3& q, const Vec3& ng) const {
    const Vec3 d = q - p;
    const float d2 = dot(d, d), cosQ = std::abs(dot(ng, d)) / std::sqrt(d2);
    if (!(d2 > 0.f && cosQ > 0.f)) return 0.f;
    const double pA = mEmitterPower[size_t(emitter)] / mWeightSum;
    return float(pA * d2 / cosQ);
}

// A point drawn ∝ power; Li = L / pdf, the pdf in solid angle for multiple importance sampling.
bool SurfaceLight::sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                            LightSample* out) const {
    const size_t k = chooseTriangle(&u1);
    Vec3 n;
    const Vec3 q = pointOn(k, u1, u2, &n);
    const int m = mTris.emitter[k];
    out->pdf = pdfAt(m, p, q, n);
    if (!(out->pdf > 0.f) || !std::isfinite(out->pdf)) return false;
    out->distance = length(q - p);
    out->wi = (q - p) / out->distance;
    out->Li = mTris.radiance[size_t(m)].sample(w) / out->pdf;
    return true;
}

// dΦ = L cos θ dA dω on each side: the point ∝ power, a side at random (each carries half), the
// direction cosine-weighted about it; every photon then carries Φ/N exactly (weight 1). The
// origin is pushed off the surface to the side it leaves, as a ray spawned at a surface is.
bool SurfaceLight::emitPhoton(const Bounds3&, Sampler& s, PhotonEmission* out) const {
    float u1 = s.get1D();
    const float u2 = s.get1D();
    const size_t k = chooseTriangle(&u1);
    Vec3 n;
    const Vec3 q = pointOn(k, u1, u2, &n);
    const float side = s.get1D() < 0.5f ? 1.f : -1.f;
    n = n * side;
    const float u3 = s.get1D(), u4 = s.get1D();
    out->direction = Frame(n).toWorld(sampleCosineHemispherePolar(u3, u4));
    out->origin = q + n * surfaceEpsilon(q);
    const auto& lambda = mLambda[size_t(mTris.emitter[k])];
    out->lambda = lambda->sample(s.get1D());
    out->weight = 1.f;
    return true;
}

std::string SurfaceLight::describe() const {
    return "emissive surfaces: " + std::to_string(triangleCount()) + " triangles, " +
           numStr(mPower) + " W";
}

}  // namespace mirage
