// Point, spot and sphere lights (lamp.cpp): a lamp at a point, or a sphere of radius r about
// it, whose intensity by direction is its profile's (light/emission_profile.h). light.h's
// makePointLight and makeSpotLight make the point forms; makeLamp any of them.
#pragma once

#include <memory>

#include "light/emission_profile.h"
#include "light/light.h"

namespace mirage {

struct LampDesc {
    Vec3 position;
    float radius = 0.f;  // m; > 0: a sphere
    float powerW = 100.f;
    ProfileDesc profile;
};

// What drawing distances towards a lamp needs beyond Light::origin() (render/lamp_sampling.h):
// its radius, and the apex of the cone outside which it sends nothing — its centre for a
// point, behind it for a sphere (lamp.cpp).
class Lamp : public Light {
public:
    virtual float radius() const = 0;
    virtual Vec3 coneApex() const = 0;
};

std::unique_ptr<Light> makeLamp(const LampDesc& desc, const Spectrum& colour);

}  // namespace mirage
