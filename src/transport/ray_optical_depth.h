// Deterministic optical depth along one ray, for transmittance at any wavelength.
//
// The photon estimates weight each photon by the transmittance T(λ_p) from the camera to the
// photon's projection on the camera ray, at the photon's own wavelength λ_p, which is none of
// the path's 4 hero wavelengths. Ratio tracking would need one stochastic walk per photon;
// instead the ray is marched once and the concentration of every component is integrated:
//
//     τ_c(t) = ∫₀ᵗ k_c(s) ds,  k_c = concentration_c · densityScale · grid_c(x(s))   (m)
//     T(t, λ) = exp(−Σ_c σt,c(λ) τ_c(t)),  σt,c = σa,c + σs,c  (1/m per unit concentration)
//
// Components whose cross-sections do not depend on λ (ComponentModel::grey) are folded into one
// grey channel that holds σt,c·τ_c directly, so a grey scene costs one channel whatever its
// component count.
//
// Every other component writes σt(C, λ) as Σ_m w_m(λ) C^p_m (ComponentModel::depthPowers): one
// channel per power integrates ∫ C^p_m ds, and the component combines them at a wavelength
// (ComponentModel::opticalDepth). A linear component has one power, 1; chlorophyll, whose σ is
// not linear in C, has the powers its law needs (medium/component.cpp).
//
// Quadrature: the midpoint rule on intervals of h = stepVoxels × the finest voxel of the media
// the ray crosses (a majorant cell for a homogeneous medium), clipped to each medium's box so
// that the entry and exit of a constant medium are exact. The trilinear field is smooth within
// a voxel, so with the default h = ½ voxel the relative error of τ is far below the photon
// estimate's own (O(h²f″/24) per interval). Between nodes τ is interpolated linearly. At most
// kMaxNodes intervals per ray; a longer ray gets a coarser step.
//
// The march is a bias, not noise: it does not fall with more photons. On the sharpest field a
// grid holds (voxels 0 or 1 at random) it measured, per ray, on the light an estimate gathers
// (∫ T σt dt): mean −8e-5, RMS 1.4e-3 at σt = 4/m and mean −4.4e-3, RMS 6.6e-3, worst 2.2e-2
// at σt = 40/m, against ~0.1 RMS per pixel of photon noise at the final quality preset
// (tests/unit/volume_estimate_test.cpp holds it below a tenth of that).
//
// One instance per thread: it holds grid accessors and reuses its buffers, so marching
// allocates nothing once the buffers have grown to the longest ray.
#pragma once

#include <vector>

#include "medium/medium.h"

namespace mirage {

class RayOpticalDepth {
public:
    static constexpr int kMaxNodes = 8192;
    // The grey optical depth at which the march stops: T = e^−30 ≈ 10^−13 there, so nothing
    // beyond can add to a photon estimate more than 10^−13 of what it would add unattenuated,
    // far below any estimate's noise. Only the grey channel is tested: the spectral ones only
    // add to τ, so the grey τ is a lower bound at every wavelength.
    static constexpr float kOpaqueDepth = 30.f;

    explicit RayOpticalDepth(const std::vector<const Medium*>& media, float stepVoxels = 0.5f);
    // Out of line: the accessors are NanoVDB's types (volume/grid_lookup.h).
    RayOpticalDepth(RayOpticalDepth&&) noexcept;
    RayOpticalDepth& operator=(RayOpticalDepth&&) noexcept;
    ~RayOpticalDepth();

    // Tabulates τ along worldRay (unit direction) over [0, tMax].
    void march(const Ray& worldRay, float tMax);
    // The time (s from the frame, motion blur) of the rays marched from now on: moving media
    // are read where MediumMotion::Path::lookupPoint says.
    void setTimeOffset(float seconds) {
        mTime = seconds;
        for (MediumInfo& m : mMedia) m.context.setTimeOffset(seconds);
    }
    float timeOffset() const { return mTime; }

    // The span of the last ray that lies inside some medium's box; empty when tBegin ≥ tEnd.
    float tBegin() const { return mT0; }
    float tEnd() const { return mT1; }
    bool empty() const { return !(mT0 < mT1); }
    float step() const { return mH; }
    // The ray parameter beyond which the last ray is opaque (T < e^−kOpaqueDepth at every
    // wavelength): where the march stopped, or infinity if it crossed every medium.
    float reach() const { return mOpaque ? mT1 : kInfinity; }
    // True when every component is grey: T does not depend on λ.
    bool grey() const { return mSpectral.empty(); }

    // Transmittance from the ray origin to t at wavelength lambdaNm (nm).
    float transmittance(float t, float lambdaNm) const;

private:
    // A component whose σt varies with wavelength: channels first, first + 1, … hold the
    // integrals of its depthPowers().
    struct SpectralComponent {
        const ComponentModel* model;
        int first;
    };
    // What one medium contributes to the channels at a point.
    struct Term {
        int grid;      // index into the medium's grids, -1 for a constant component
        float scale;   // concentration · densityScale, times σt for the grey channel
        int channel;   // 0 = grey
        float exponent = 1.f;  // the channel integrates (scale · grid)^exponent
    };
    struct MediumInfo {
        explicit MediumInfo(const Medium* m);
        const Medium* medium;
        std::vector<Term> terms;
        std::vector<FloatGrid::Accessor> accessors;
        Medium::Context context;  // the medium's time and velocity accessor
        float voxel;  // finest object-space voxel (a majorant cell when it has no grid)
    };
    std::vector<MediumInfo> mMedia;
    // Linear components first, then the others: the order their optical depths are summed in.
    std::vector<SpectralComponent> mSpectral;
    int mChannels = 1;
    float mStepVoxels;
    float mTime = 0.f;

    // The last march: nodes at mT0 + j·mH, j = 0..mNodes, τ per channel per node.
    float mT0 = 0.f, mT1 = 0.f, mH = 1.f;
    int mNodes = 0;
    bool mOpaque = false;     // the march stopped at kOpaqueDepth, before the media's far side
    std::vector<float> mTau;  // (mNodes + 1) × mChannels
    // Per medium crossed by the last ray: its object-space ray and span.
    struct Span {
        int medium;
        Ray objectRay;
        float t0, t1;
    };
    std::vector<Span> mSpans;
    // Adds span s's integral over each node interval to the increments in mTau.
    void addSpan(const Ray& ray, const Span& s);
};

}  // namespace mirage
