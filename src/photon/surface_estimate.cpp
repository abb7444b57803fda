#include "photon/surface_estimate.h"

#include "spectrum/cie.h"

namespace mirage {

SurfacePhotons::SurfacePhotons(PhotonList photons) : mMap(std::move(photons)) {
    // Φ_p cmf(λ_p) / ∫ȳ: the photon's flux as the film's XYZ (volume_estimate.h).
    mFluxXyz.resize(mMap.size());
    for (size_t i = 0; i < mMap.size(); ++i)
        mFluxXyz[i] = cieXyz(mMap[i].lambda) * (mMap[i].power / kCieYIntegral);
}

}  // namespace mirage
