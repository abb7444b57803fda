// The photons as the radiance estimates see them, and the conventional volume radiance
// estimate (Jensen & Christensen 1998); the beam estimate is in beam_estimate.h.
//
// Photons are monochromatic and camera paths carry 4 hero wavelengths, so the photon
// estimates produce CIE XYZ directly instead of a SampledSpectrum. Derivation: the stored
// photons estimate the spectral flux density of the scattering events,
//     E[Σ_p Φ_p δ(x − x_p) δ(ω − ω_p) δ(λ − λ_p)],
// so any radiance estimate built from them has the form L(λ) = Σ_p w_p Φ_p δ(λ − λ_p), with w_p
// the geometric weight of photon p (kernel, transmittance, phase; m⁻²·sr⁻¹) and δ in 1/nm. The
// film stores X = ∫ L(λ) x̄(λ) dλ / ∫ȳ dλ (film.cpp; the same normalisation as spectrumToXyz),
// and the δ turns the wavelength integral into an evaluation at λ_p:
//     XYZ = Σ_p w_p Φ_p cmf(λ_p) / ∫ȳ,
// with Φ_p in W, cmf dimensionless and ∫ȳ = kCieYIntegral in nm: W·m⁻²·sr⁻¹·nm⁻¹, the film's
// units. The wavelength integral is done by the photon pass's sampling of λ_p, exactly as the
// hero wavelengths do it for the camera paths, so the two parts add in the same pixel sum.
#pragma once

#include <algorithm>
#include <vector>

#include "medium/medium.h"
#include "medium/phase.h"
#include "photon/photon_groups.h"
#include "photon/photon_map.h"
#include "photon/view_weight.h"
#include "transport/ray_optical_depth.h"

namespace mirage {

// σs(x, λ) summed over the media whose box contains x, for one thread (grid accessors).
class ScatteringProbe {
public:
    explicit ScatteringProbe(const std::vector<const Medium*>& media);
    float sigmaS(const Vec3& worldP, float lambdaNm);
    // The density of fluorescent re-emission events at x for light absorbed at λi (1/m):
    // Σ_media Σ_c Γ_c σa,c(x, λi) over the fluorescent components (transport/reemission.h).
    float reemissionDensity(const Vec3& worldP, float lambdaInNm);
    // The density of the events photon p stands for at x: σs(x, λ_p) for a scattering,
    // reemissionDensity(x, λi) for a re-emission.
    float eventDensity(const Vec3& worldP, const Photon& p) {
        return p.reemitted() ? reemissionDensity(worldP, p.lambdaIn) : sigmaS(worldP, p.lambda);
    }
    // True when no medium's σs varies with wavelength and none fluoresces: σs(x) may then be
    // taken once per point.
    bool grey() const { return mGrey; }
    // The time (s from the frame, motion blur) at which the media are probed.
    void setTimeOffset(float seconds) {
        for (auto& c : mContexts) c.setTimeOffset(seconds);
    }

private:
    std::vector<const Medium*> mMedia;
    std::vector<Medium::Context> mContexts;
    std::vector<float> mSigmaA;  // scratch: one medium's σa per component
    bool mGrey = true;
};

// The kd-tree plus, per slot, what every estimate needs of a photon: its flux as XYZ, its
// phase function and the density of its kind of event where it was stored.
//
// Fluorescent re-emissions (Photon::reemitted) are photons of the same map: the inelastic
// source term of the transfer equation (Gutierrez et al. 2005), S(x, ω, λo) = (1/4π) ×
// the power re-emitted per unit volume and wavelength, is estimated by the same kernels as the
// elastic σs L_s, with the isotropic lobe 1/(4π) in place of the medium's phase function.
class VolumePhotons {
public:
    VolumePhotons() = default;
    // Builds the kd-tree. The phase function of photon p is the mixture of the HG lobes of every
    // medium component, weighted by σs,c(x_p, λ_p): one medium evaluation per photon, here,
    // and only when the lobes differ (a single lobe needs no weights). xyzPerWatt, where the
    // scene is achromatic (render/achromatic_film.h), holds per light (Photon::light) the
    // expectation of cmf(λ_p)/∫ȳ over that light's wavelengths: every photon's flux is then
    // Φ_p × xyzPerWatt[light], its light's exact colour, instead of Φ_p cmf(λ_p)/∫ȳ (the same
    // mean, no colour noise); empty: each photon at its own wavelength.
    VolumePhotons(PhotonList photons, const std::vector<const Medium*>& media,
                  const std::vector<Vec3>& xyzPerWatt = {});

    const PhotonMap& map() const { return mMap; }
    // The media the photons were traced in (they must outlive this object).
    const std::vector<const Medium*>& media() const { return mMedia; }
    size_t size() const { return mMap.size(); }
    // Φ_p cmf(λ_p) / ∫ȳ, W (see above), or Φ_p × xyzPerWatt[light].
    const Vec3& fluxXyz(size_t slot) const { return mFluxXyz[slot]; }
    // p(wi_p, wo) in 1/sr: the photon arrived along wi_p and leaves towards the camera along wo;
    // 1/(4π) for a re-emission.
    float phase(size_t slot, const Vec3& wo) const;
    // The density of the events the photon samples at x_p (1/m): σs(x_p, λ_p), or for a
    // re-emission Σ_c Γ_c σa,c(x_p, λi) (ScatteringProbe::eventDensity).
    float sigmaS(size_t slot) const { return mSigmaS[slot]; }

private:
    PhotonMap mMap;
    std::vector<const Medium*> mMedia;
    std::vector<float> mSigmaS;
    std::vector<Vec3> mFluxXyz;
    std::vector<ComponentPhase> mLobes;
    std::vector<float> mLobeWeights;  // size() × mLobes.size(), empty for a single lobe
};

// A search for the k nearest photons (k ≥ 2) within maxRadius (m), into `buffer` (k entries).
struct PhotonSearch {
    int k;
    float maxRadius;
    PhotonNeighbour* buffer;
};

// The volume radiance estimate at x (Jensen & Christensen 1998, eq. 5):
//     σs(x) L_s(x, wo) ≈ (k − 1)/k · Σ_{k nearest} p(x, wi_k, wo) ΔΦ_k / ((4/3) π r³),
// r the distance to the k-th nearest photon, or maxRadius (and no (k − 1)/k) when fewer than
// k lie within it. Returned as XYZ, W·m⁻³·sr⁻¹·nm⁻¹: the in-scattered radiance per metre of
// camera ray, σs included (the 1/σs of the estimate cancels the σs of the in-scattering term).
// The factor (k − 1)/k is not in the paper. Without it the mean for a uniform Poisson density
// ρ is ρ·k/(k − 1), not ρ: the ball's radius is set by its k-th photon, and E[1/V_k] =
// ρ/(k − 1) for the volume V_k of that ball. That bias does not fall with the photon count at
// fixed k; on the convergence scene (tests/physics) it measured +5.4 % at k = 16 and +2.9 % at
// k = 32 with 10⁶ photons. With a fixed ball (fewer than k found) the plain sum is unbiased.
Vec3 pointEstimate(const VolumePhotons& photons, const Vec3& x, const Vec3& wo,
                   const PhotonSearch& search);

// The σs ratio σs(x)/σs(x_i) by which an estimate moves a photon's light from where it was
// stored to x (below, and beam_estimate.h), capped. A photon stored where the smoke is thin
// stands for a fluence of ΔΦ/σs(x_i): rare, and heavy. Its disc or search ball (wide there: few
// photons) may reach a camera ray in smoke a hundred times denser, and the ratio then makes one
// photon a blotch of pixels tens of times too bright. In one pass of a race on
// mantaflow_smoke.0010, one such photon put 90 % of the image's error into 4 pixels, and 8
// passes had 3.4x the error of 2 (docs/performance-history.md, "A cap on the density ratio").
// Capped at 16 the heavy tail is gone: relMSE at 8 passes 0.279 → 0.025 there, 0.040 → 0.033 on
// smoke1, whose mean moves by −1 % (0.999 → 0.989 of the path tracer's). The cap bites only
// where a kernel spans a 16-fold change of σs; as the progressive radii shrink, a kernel on a
// continuous (trilinear) field spans less and less of a change, so the estimate stays
// consistent.
constexpr float kMaxDensityRatio = 16.f;
inline float cappedDensityRatio(float here, float atPhoton) {
    return std::min(here / atPhoton, kMaxDensityRatio);
}

// The march of the point estimate along a camera ray: steps of `step` metres shifted by u·step,
// u ∈ [0, 1) per camera sample, σs read at each point by `probe`.
struct PointMarch {
    float step;
    float u;
    ScatteringProbe* probe;
};

// The ray-marched estimate of ∫ T(t) σs L_s(t) dt over the span of `depth` (already marched
// along `ray`): the midpoint rule of `march`, which its shift makes unbiased for the integral
// of the point estimate. Each photon is
// attenuated by T(t, λ_p) at its own wavelength, and weighted by σs(x, λ_p)/σs(x_p, λ_p): a
// photon samples the fluence where it was stored as ΔΦ/σs(x_p) per unit volume, and the march
// point in-scatters it with its own σs(x). In a uniform medium the ratio is 1 (the paper's
// form); in a heterogeneous one, without it, the kNN ball carries light from dense smoke into
// thin smoke and empty space (measured +15 % on the mean of smoke1.vdb against volpath). A
// re-emitted photon is weighted likewise by the ratio of re-emission densities, Σ Γ σa,c(λi)
// at x over the same at x_p (a chlorophyll plume re-emits where its chlorophyll is).
// `view` weights each photon by what the camera path puts in front of this ray (view_weight.h);
// `groups`, when active, receives the estimate split by light group (photon_groups.h).
Vec3 pointEstimateAlongRay(const VolumePhotons& photons, const Ray& ray,
                           const RayOpticalDepth& depth, const PhotonSearch& search,
                           const PointMarch& march, const ViewWeight& view = ViewWeight(),
                           const PhotonGroups& groups = PhotonGroups());

}  // namespace mirage
