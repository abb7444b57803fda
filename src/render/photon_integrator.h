// The photon-map integrator's face (photon_integrator.cpp holds the estimator and its account):
// its settings, the figures it reports, the factory, its photon pass alone for `mirage photons`,
// and the test that sends photons along curved paths. Only what renders or configures photons
// includes this; the integrator interface (integrator.h) knows none of it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "photon/photon_pass.h"
#include "render/integrator.h"

namespace mirage {

enum class PhotonEstimate { Beam, Point };

// [render] final_gather's default (docs/scene-file.md; measured in docs/performance.md).
constexpr int kDefaultFinalGather = 4;
constexpr int kMaxFinalGather = 4096;

// Settings of the photon-map integrator (scene file: [render] photons, estimate, k,
// max_radius). The photon pass's own settings are the base, set as a user asks for them: the
// number of photons, the render seed (each pass derives its own from it), the bounce cap, the
// progress mode and the curved light of a [refraction] field (followed only where it curves
// within the scene's bounds: photonsCurve). What each pass derives from the scene (the first
// interaction stored or not, the shutter) the integrator sets itself. Zeros select the
// defaults noted.
struct PhotonIntegratorSettings : PhotonPassSettings {
    // Emitted in the first photon map, the only one of a render not in passes; 0: photons. A
    // render in passes whose first pass is smaller starts sooner (photon_integrator.cpp).
    uint64_t firstPassPhotons = 0;
    PhotonEstimate estimate = PhotonEstimate::Beam;
    int k = 0;              // photons per estimate, ≥ 2; 0: 16 (beam radii), 32 (point)
    float maxRadius = 0.f;  // m; 0: a tenth of the diagonal of the media's bounds
    float marchStep = 0.f;  // m, point estimate; 0: half the median k-nearest radius
    // Final gather rays at the camera path's first diffuse surface (photon_integrator.cpp); 0:
    // indirect light read straight from the global map there.
    int finalGather = kDefaultFinalGather;
    // --photons-file: the maps of this frame's pass, saved by `mirage photons`; preprocess()
    // builds its maps from them instead of tracing (the same photons, so the same bits).
    std::shared_ptr<const PhotonPassResult> savedPass;

    int kOrDefault() const { return k > 0 ? k : (estimate == PhotonEstimate::Beam ? 16 : 32); }
    uint64_t photonsOfPass(int pass) const {
        return pass == 0 && firstPassPhotons > 0 ? firstPassPhotons : photons;
    }
};

// Figures of the photon integrator, for the render summary and the EXR header (metadata() gives
// them as snake_case keys, written as mirage:<key>): its photon passes' own, summed over the
// passes, and the time its maps and estimates took. Seconds are wall time, except
// estimateSeconds: thread time summed over the render threads.
struct PhotonStats {
    PhotonPassStats traced;            // the photon passes (emitted, stored, seconds, …)
    double photonMapBuildSeconds = 0;  // kd-trees of the volume and surface maps
    double photonRadiiSeconds = 0;     // beam: k-nearest disc radius of every volume photon
    double discBvhBuildSeconds = 0;    // beam: Embree BVH over the photon discs
    double estimateSeconds = 0;        // beam/point and surface estimates, all threads
    double photonsPerSecond() const {  // traced / pass seconds
        return traced.seconds > 0 ? double(traced.emitted) / traced.seconds : 0.0;
    }
    std::vector<std::pair<std::string, std::string>> metadata() const;
};

// Volumetric photon mapping (Jensen & Christensen 1998) with the beam radiance estimate
// (Jarosz et al. 2008) or the ray-marched point estimate for multiple scattering; single
// scattering and emission as the single-scatter integrator computes them.
std::unique_ptr<Integrator> makePhotonIntegrator(const PhotonIntegratorSettings& settings);

// The photon integrator's photon pass alone, exactly as its preprocess() traces it for `scene`
// (`mirage photons`: pass 0; a render in passes traces pass p > 0 with a seed of its own);
// settings.savedPass is ignored.
PhotonPassResult tracePhotonIntegratorPass(const RenderScene& scene,
                                           const PhotonIntegratorSettings& settings, int pass = 0);

// Whether photons follow curved paths: a field whose |∇n| bound over the scene's bounds (grown
// by a tenth of their diagonal) is not 0. Then shadow rays do not exist (they would be straight)
// and the photon integrator takes direct light from the photon maps (Gutierrez et al. 2005).
bool photonsCurve(const IndexField* field, const Bounds3& sceneBounds);

}  // namespace mirage
