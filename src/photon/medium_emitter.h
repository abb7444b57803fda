// Photon emission from an emissive medium (fire): the medium is a light whose emitted spectral
// power density is 4π σa(x,λ) Le(x,λ) (W·m⁻³·nm⁻¹; Kirchhoff, Le = intensity · B(λ, T(x)),
// isotropic), so its power over the visible range is Φ = 4π ∫_V ∫_360^830 σa Le dλ dx.
//
// Cells. The emission field is what the render pass sees: trilinear lookups of the grids. Its
// natural pieces are the dual cells of the temperature grid, the cubes whose 8 corners are voxel
// centres: inside one, every trilinear field is an interpolation of its corners. A cell's
// tabulated power is V_cell × the mean over its corners of q = 4π ∫ σa Le dλ (W/m³), so the
// table sums to Σ_voxels q_v V_voxel, the voxel (midpoint) integral of the grid; for an
// isothermal, homogeneous block of voxels this is exactly 4π σa V ∫ Le dλ.
//
// Sampling (Jensen 2001 §5.1 for lights, here for a volume): a cell ∝ its tabulated power, a
// uniform point in it, λ ∝ B(λ, T_hot) v(λ) (inverse CDF, spectrum/spectrum_sampling.h) with
// T_hot the cell's hottest corner and v the camera's own wavelength density
// (SampledWavelengths::visiblePdf), an isotropic direction. The table is an approximation of
// the field inside a cell, so each photon carries the weight
//     w = f(x, λ) V_cell / (Φ_cell p_cell(λ)),   f = 4π σa(x,λ) Le(x,λ),
// which makes the photon pass unbiased for the exact field: inside an isothermal, homogeneous
// block w ∝ 1/v(λ), and its mean over all photons is Φ_true / Φ_table. Planck's law grows with
// T at every λ, so the hottest corner's spectrum keeps w bounded, and v > 0 over 360–830 nm.
// Why v: a flame at 1500–1800 K puts ~70 % of its 360–830 nm power above 700 nm, where the
// colour-matching functions are nearly 0; drawn ∝ B alone, most photons would carry light the
// film barely sees, and the few visible ones make the lit smoke blotchy in colour. Drawn ∝ B v,
// the photons sit where the eye looks and carry power ∝ 1/v (more in the deep red).
//
// Not covered: emission where every corner of a cell has q = 0 but its interior does not (a hot
// corner without absorber next to an absorbing cold one: the interpolated interior emits a
// little), tiles of the root node (4096³ voxels), and a temperature offset that makes the
// background itself hotter than min_temperature. These leave out a sliver of emission; the
// render pass still sees it directly.
#pragma once

#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "light/light.h"
#include "medium/medium.h"
#include "spectrum/spectrum_sampling.h"

namespace mirage {

class MediumEmitter {
public:
    // Builds the power table of an emissive medium (one with an [emission] table).
    explicit MediumEmitter(const Medium& medium);

    const Medium& medium() const { return *mMedium; }
    // Σ of the tabulated cell powers (W over 360–830 nm).
    double tablePower() const { return mTotal; }
    size_t cells() const { return mCells.size(); }
    // Emitting voxels of the temperature grid (corners with q > 0).
    size_t emittingVoxels() const { return mEmittingVoxels; }

    // Each cell of the table as its object-space centre and its tabulated power (W): what the
    // camera paths' coarse grid of emitted power is summed from (render/emission_light.h).
    struct CellPower {
        Vec3 centre;
        double power;
    };
    std::vector<CellPower> cellPowers() const;
    // A cell's edges in object space: the temperature grid's voxel size.
    Vec3 cellSize() const;

    // Draws one photon (origin, isotropic direction, wavelength, weight w as above). ctx is a
    // context of this medium; its wavelengths are changed. Returns false when the table is
    // empty or the drawn point emits nothing at λ (weight 0).
    bool sample(Sampler& sampler, Medium::Context& ctx, PhotonEmission* out) const;

    // q(x) = 4π ∫_360^830 σa(x,λ) Le(x,λ) dλ (W/m³) at an object-space point: the λ-integral of
    // the emission that Medium::eval returns, from tables over temperature.
    double powerDensity(const Vec3& pObject) const;

private:
    struct Cell {
        int32_t i, j, k;   // index of the lower corner in the temperature grid
        uint16_t sampler;  // Planck sampler of the hottest corner (mSamplers)
    };
    // An emitting voxel of the temperature grid: its key (packed index), q (W/m³) and T (K).
    struct Corner {
        uint64_t key;
        float q, T;
    };
    // The constructor's steps (medium_emitter.cpp).
    void tabulateIntegrals(float tMax);
    void tabulateSamplers(float tMax);
    std::vector<Corner> emittingCorners(const FloatGrid& temperature) const;
    void tabulateCells(const std::vector<Corner>& corners);
    // ∫ σa_c(λ) B(λ,T) dλ per linear component, tabulated over T (K); the Planck CDFs.
    double componentIntegral(int component, float T) const;
    int samplerIndex(float T) const;
    double powerDensityAt(const Vec3& pObject, const std::vector<FloatGrid::Accessor>& acc) const;

    const Medium* mMedium;
    float mTMin = 0, mTStep = 1, mSamplerStep = 1;
    std::vector<std::vector<float>> mIntegral;  // per component, per T step (W·m⁻²·sr⁻¹ · 1/m)
    std::vector<SpectrumSampler> mSamplers;  // B(λ, T) v(λ) at T = mTMin + k · mSamplerStep
    std::vector<Cell> mCells;
    std::vector<double> mCdf;  // cumulative cell power (W)
    double mTotal = 0.0;
    double mCellVolume = 0.0;  // world m³ of one dual cell
    size_t mEmittingVoxels = 0;
};

}  // namespace mirage
