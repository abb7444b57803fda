// Lights. Every light carries a spectral power distribution normalised to ∫ S(λ) dλ = 1 over
// 360–830 nm (1/nm), scaled by its power in watts (point, spot, quad) or its irradiance in W/m²
// (distant): "100 W" means 100 W radiated over the visible range, whatever the colour.
//
// Lights serve both passes: the render pass samples incident light at a point (sampleLi), the
// photon pass emits photons (emittedPower, emitPhoton) with origin and direction drawn ∝ the
// emitted radiance and the wavelength ∝ the spectral power distribution (Jensen 2001, §5.1).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/spectral.h"
#include "light/projection.h"
#include "spectrum/spectrum.h"

namespace mirage {

struct LightSample {
    Vec3 wi;             // unit direction from the shaded point towards the light
    float distance;      // to the light (kInfinity for distant lights)
    SampledSpectrum Li;  // incident radiance divided by the sampling pdf (W·m⁻²·nm⁻¹)
    // Solid-angle pdf of wi for a light a sampled direction can hit (the quad, the dome), for
    // multiple importance sampling against the phase function (render/direct_light.cpp); 0 for
    // lights a direction cannot hit (point, spot, distant: no MIS).
    float pdf = 0.f;
};

// One photon leaving a light. Of N photons emitted from a light of power Φ, each carries
// Φ/N × weight watts at its single wavelength: the origin, direction and wavelength are drawn
// ∝ the emitted spectral radiance, so that Φ/N is the exact, unbiased share of each.
struct PhotonEmission {
    Vec3 origin;     // world metres
    Vec3 direction;  // unit
    float lambda;    // nm, drawn from the normalised spectral power distribution
    // Emitted radiance over the density the direction was drawn with, scaled to mean 1. It is
    // 1 wherever the emission is sampled exactly; a spot light samples a cone uniformly in
    // solid angle and carries its falloff here (mean 1 over its own cone, less over the
    // narrower cone of a scene seen from afar).
    float weight = 1.f;
};

// Where a light at a point sits, for drawing distances along a ray towards it
// (transport/equiangular.h): its position, and the cone outside which it sends nothing
// (cosCone −1: every direction).
struct LightOrigin {
    Vec3 p;
    Vec3 axis{0.f, 0.f, 1.f};
    float cosCone = -1.f;
};

struct LightLobe {
    Vec3 dir;
    float irradiance = 0.f;
};

class Light {
public:
    virtual ~Light() = default;
    // Samples incident light at p. Returns false when p receives nothing from this sample.
    virtual bool sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                          LightSample* out) const = 0;
    // Power the light sends towards a scene bounded by sceneBounds (W). Spot and quad lights:
    // their power. A point light outside the bounding sphere of sceneBounds: the share of its
    // power in the cone that sphere subtends (its photons are aimed there; inside: all of
    // it). A distant light: its irradiance × the area of the disc covering that sphere, seen
    // along the light (0 for empty bounds).
    virtual float emittedPower(const Bounds3& sceneBounds) const = 0;
    // Draws one photon. Returns false when the light emits nothing into the scene.
    virtual bool emitPhoton(const Bounds3& sceneBounds, Sampler& sampler,
                            PhotonEmission* out) const = 0;
    // The light's projection map onto the specular objects (light/projection.h): what it emits
    // towards them alone, for the caustic photons. Null where the light has none (quad and
    // surface lights: their caustic photons come from their ordinary emission) or no target
    // can receive its light.
    virtual std::unique_ptr<PhotonProjection> projection(const ProjectionTargets&) const {
        return nullptr;
    }
    virtual std::string describe() const = 0;
    // Radiance seen along d by a ray that leaves the scene (W·m⁻²·sr⁻¹·nm⁻¹): 0 but for lights at
    // infinity (the dome). cameraRay: the ray is the camera's own, before any bounce, which a
    // light may hide from (a dome that lights the scene without being its background).
    virtual SampledSpectrum escapedRadiance(const Vec3&, const SampledWavelengths&,
                                            bool /*cameraRay*/) const {
        return SampledSpectrum(0.f);
    }
    // A light with an area or at infinity (the dome): whether the ray from p along the unit
    // direction wi meets its emitting side; then *out holds the distance, the radiance itself
    // (Li, not divided by a pdf) and the pdf sampleLi would draw wi with. The others: false.
    virtual bool hitLi(const Vec3& /*p*/, const Vec3& /*wi*/, const SampledWavelengths&,
                       LightSample* /*out*/) const {
        return false;
    }
    // True for lights at infinity, which escaped rays see (escapedRadiance).
    virtual bool infinite() const { return false; }
    // A light at infinity of one radiance from every direction (the constant dome): the phase
    // function's or the BSDF's own samples of it score f/pdf × L, bounded, which its samples
    // can only match (render/direct_light.cpp).
    virtual bool uniformRadiance() const { return false; }
    // The spectral shape of everything the light sends (any scale) when sampleLi's Li is that
    // spectrum times a factor independent of λ: every light here. Null for a light whose
    // colour varies over directions or points (render/achromatic_film.h then samples colour).
    virtual const Spectrum* spectrum() const { return nullptr; }
    // The fixed spectra whose combination, with coefficients free of λ that may vary over
    // directions or points, is everything the light sends: its spectrum() where it has one; an
    // image dome's three basis windows (light/dome_light.cpp). Empty: none such.
    virtual std::vector<const Spectrum*> spectralShapes() const {
        if (const Spectrum* s = spectrum()) return {s};
        return {};
    }
    // A light at a point (point, spot): where it is. The others: nothing.
    virtual std::optional<LightOrigin> origin() const { return std::nullopt; }
    // A light at infinity most of whose power comes from one small patch of sky (a sun in a
    // sky map): the direction towards the patch and the patch's irradiance, mean over
    // 360–830 nm (W·m⁻²·nm⁻¹, the unit of a distant light's Li). The others: nothing.
    virtual std::optional<LightLobe> lobe() const { return std::nullopt; }
};

// Normalises a colour spectrum so that ∫ S dλ = 1 over 360–830 nm.
Spectrum normalizedPowerSpectrum(const Spectrum& colour);

std::unique_ptr<Light> makePointLight(const Vec3& position, float powerW, const Spectrum& colour);
// A spot light aimed along `direction`; full intensity inside coneInner, smooth falloff to
// coneOuter (half-angles in degrees). Power is the total radiated into the cone.
std::unique_ptr<Light> makeSpotLight(const Vec3& position, const Vec3& direction, float powerW,
                                     float coneInnerDeg, float coneOuterDeg,
                                     const Spectrum& colour);
// Parallel light travelling along `direction` with irradiance E (W/m²) on a surface facing it.
std::unique_ptr<Light> makeDistantLight(const Vec3& direction, float irradiance,
                                        const Spectrum& colour);
// One-sided Lambertian quad emitting along normalize(cross(edgeU, edgeV)), radiance
// L = Φ / (π A).
std::unique_ptr<Light> makeQuadLight(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV,
                                     float powerW, const Spectrum& colour);

}  // namespace mirage
