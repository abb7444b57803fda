// The scene's emissive triangles (meshes and quads of a diffuse material with `emission`) as
// one light, so that next-event estimation and the photon pass find them, not only the rays
// that happen to hit them.
//
// Each emitter is a two-sided Lambertian surface of constant radiance L_m(λ) (its material's
// emission, W·m⁻²·sr⁻¹·nm⁻¹), as the camera path sees it when it hits one. Shadow rays draw a
// triangle ∝ its area times ∫ L_m dλ (its power), then a point uniformly on it; the density
// of a point of emitter m is therefore the same on every triangle of that emitter,
// p_A = ∫ L_m dλ / Σ_k A_k ∫ L_k dλ, and the pdf of any point a ray hits (pdfAt) needs only its
// emitter, not which triangle it is: that is what multiple importance sampling against the BSDF
// and phase function needs (render/direct_light.cpp). Photons leave the same points, on either
// side with a cosine-weighted direction, their wavelength by the emitter's spectrum.
#pragma once

#include <memory>
#include <vector>

#include "core/distribution.h"
#include "light/light.h"
#include "light/light_common.h"
#include "spectrum/spectrum_sampling.h"

namespace mirage {

struct EmissiveTriangles {
    std::vector<Vec3> vertices;      // world metres, 3 per triangle
    std::vector<int> emitter;        // per triangle: its index into `radiance` (its material)
    std::vector<Spectrum> radiance;  // per emitter; zero for one that emits nothing
    std::vector<bool> shapes;        // per shape of the scene: whether its triangles are here
};

class SurfaceLight : public Light {
public:
    // emittedPower() is 0 when no triangle has both an area and an emission: then the light
    // is no use (addSurfaceLight leaves it out).
    explicit SurfaceLight(EmissiveTriangles triangles);
    bool sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                  LightSample* out) const override;
    float emittedPower(const Bounds3&) const override { return mPower; }
    bool emitPhoton(const Bounds3&, Sampler& s, PhotonEmission* out) const override;
    std::string describe() const override;
    // The solid-angle pdf sampleLi draws the point q of emitter `emitter` with from p, where
    // the surface's normal there is ng: p_A d² / |cos θ_q|.
    float pdfAt(int emitter, const Vec3& p, const Vec3& q, const Vec3& ng) const;
    // Whether the triangles of the scene's shape `shape` are among this light's: then
    // next-event estimation counts its emission, and a path that hits it after a vertex that
    // sampled the lights must not (render/camera_path.cpp).
    bool samples(int shape) const {
        return shape >= 0 && size_t(shape) < mTris.shapes.size() && mTris.shapes[size_t(shape)];
    }
    // One emitter: its spectrum; several: none (the colour varies over points).
    const Spectrum* spectrum() const override {
        return mOnly >= 0 ? &mTris.radiance[size_t(mOnly)] : nullptr;
    }

private:
    EmissiveTriangles mTris;
    std::vector<double> mEmitterPower;  // per emitter: ∫ L dλ (W·m⁻²·sr⁻¹)
    Distribution1D mChoice;             // triangles ∝ A ∫ L dλ
    double mWeightSum = 0.0;            // Σ A ∫ L dλ
    float mPower = 0.f;                 // 2π Σ A ∫ L dλ: both sides, π L per unit area each
    int mOnly = -1;                     // the one emitter with power, −1 for several
    std::vector<std::shared_ptr<const SpectrumSampler>> mLambda;  // per emitter
    size_t triangleCount() const { return mTris.emitter.size(); }
    // A point uniform on triangle k (the square-root warp) and the triangle's unit normal.
    Vec3 pointOn(size_t k, float u1, float u2, Vec3* n) const;
    size_t chooseTriangle(float* u) const;
};

// The emissive surfaces among a scene's lights, or null.
inline const SurfaceLight* surfaceLightOf(const Light& light) {
    return dynamic_cast<const SurfaceLight*>(&light);
}

}  // namespace mirage
