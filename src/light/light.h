// Lights. Every light carries a spectral power distribution normalised to ∫ S(λ) dλ = 1 over
// 360–830 nm (1/nm), scaled by its power in watts (point, spot, quad) or its irradiance in W/m²
// (distant): "100 W" means 100 W radiated over the visible range, whatever the colour.
#pragma once

#include <memory>
#include <string>

#include "core/math.h"
#include "core/spectral.h"
#include "spectrum/spectrum.h"

namespace mirage {

struct LightSample {
    Vec3 wi;              // unit direction from the shaded point towards the light
    float distance;       // to the light (kInfinity for distant lights)
    SampledSpectrum Li;   // incident radiance divided by the sampling pdf (W·m⁻²·nm⁻¹)
};

class Light {
public:
    virtual ~Light() = default;
    // Samples incident light at p. Returns false when p receives nothing from this sample.
    virtual bool sampleLi(const Vec3& p, float u1, float u2, const SampledWavelengths& w,
                          LightSample* out) const = 0;
    virtual std::string describe() const = 0;
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
