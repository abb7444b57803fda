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
    float lambda;   // wavelength, nm (for a re-emission: the new wavelength λo)
    float power;    // flux carried, W (already divided by the number of emitted photons; for a
                    // re-emission: the power after it, × λi/λo)
    // A fluorescent re-emission (Gutierrez et al. 2005) rather than an elastic scattering: the
    // absorbed wavelength λi in nm, 0 for an elastic event. The light of such a photon leaves
    // isotropically (phase 1/4π, whatever the medium's lobes) at `lambda`, and the density of
    // such events is Σ_c Γ_c σa,c(x, λi), not σs(x, λ) (photon/volume_estimate.h).
    float lambdaIn = 0.f;
    // The photon's time relative to the frame (s, motion blur): the medium it met was the one
    // at this time, and its event density is taken there (volume_estimate.h).
    float time = 0.f;
    // The light the photon left (its index in the pass's lights), or kFromMedium for light
    // emitted by a medium (fire): the light-group passes split the estimates by it
    // (photon/photon_groups.h).
    uint32_t light = kFromMedium;

    static constexpr uint32_t kFromMedium = 0xffffffffu;
    bool reemitted() const { return lambdaIn > 0.f; }
};

using PhotonList = std::vector<Photon>;

}  // namespace mirage
