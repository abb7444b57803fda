// A volume photon: one stored scattering event of the photon pass (Jensen & Christensen 1998).
// Photons are monochromatic: each carries one wavelength drawn from its light's spectrum, so a
// photon's power is a plain number of watts and the spectral estimate stays unbiased.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"

namespace mirage {

struct Photon {
    Vec3 p;         // position of the scattering event, world metres
    Vec3 wi;        // unit direction the photon travelled *before* the event
    float lambda;   // wavelength, nm
    float power;    // flux carried, W (already divided by the number of emitted photons)
};

using PhotonList = std::vector<Photon>;

}  // namespace mirage
