// Emissive media (fire) as a light that camera paths aim at: the direction sampler of line
// integration (Simon, Hanika, Zirr & Dachsbacher 2017, "Line Integration for Rendering
// Heterogeneous Emissive Volumes", EGSR; §4), whose estimator is render/line_emission.h.
//
// The grid. Per emissive medium, a coarse grid over its object-space bounds (the majorant's
// bounds, kEmissionGridResolution cells along the longest axis) holding each cell's emitted
// power P_c: the photon emitter's table (photon/medium_emitter.h: per dual cell of the
// temperature grid, its volume × the mean of q = 4π ∫_360^830 σa Le dλ over its corners, W)
// spread over the coarse cells each dual cell overlaps, in proportion to the overlap. It is built
// once per frame, before the render, from the still grids; the power over 360–830 nm stands in for
// luminance, to within a factor ~1.5 over a flame's 1500–1800 K (the weight below makes any proxy
// unbiased, a poor one only noisier).
//
// Sampling a direction from x: a cell c with probability P_c / P (P = Σ over the cells of every
// emissive medium), a uniform point y in it (object space, placed in the world by the volume's
// transform at the path's time), ω = (y − x)/|y − x|. The density of ω is that of y along the
// ray x + tω, turned into solid angle by the Jacobian t²:
//     p_L(ω) = Σ_c P_c / (P V_c) ∫_{t ∈ c} t² dt = Σ_c P_c / (P V_c) (t1³ − t0³)/3,
// V_c the cell's world volume (its object volume × |det| of the transform), [t0, t1] the ray's
// span in c, summed exactly by the majorant grid's own 3D-DDA (volume/majorant_traverse.inl)
// over the whole ray: points behind a surface or beyond the first emitter draw the same ω.
// Cells that emit nothing have P_c = 0, and directions that miss every emitting cell p_L = 0:
// there the path's own flight keeps all the weight (render/line_emission.h).
//
// Sampling a distance along a line (render/line_emission.h): t ∝ the same cells' power per
// volume, P_c / (P V_c), plus a floor of kDistanceFloor × the mean of that density over the
// cells that emit, over the medium's whole bounds: the table leaves out slivers of emission
// (photon/medium_emitter.h, "Not covered"), and the floor keeps every point of the medium
// drawable (an unbiased estimate needs a density > 0 wherever σa Le > 0). Two walks of the DDA: the
// total, then the span the number falls in.
//
// Motion blur: the cells are the still medium's, placed by the transform at the path's time
// (keyed transforms move them exactly); emission that a velocity grid advects leaves them by
// up to its displacement, which the path's flight, whose weight takes it where p_L falls,
// still finds.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "render/integrator.h"

namespace mirage {

// Cells of the coarse power grid along a medium's longest axis: a flame of a 96³ cache spans
// ~10 of them. The DDA that sums p_L visits up to ~55 cells per ray.
constexpr int kEmissionGridResolution = 32;
// The distance sampler's floor over an emissive medium's bounds, relative to its density's
// mean over the cells that emit: a few per cent of the points land where nothing glows.
constexpr float kDistanceFloor = 0.01f;
// Emissive media a scene may have for its emission to be sampled as a light (a line sample
// reads them all at its point); beyond, the flights alone find it, as without.
constexpr size_t kMaxEmissiveMedia = 8;

class EmissionLight {
public:
    // The power grids of the scene's emissive media (heterogeneous media with an [emission]
    // table); null where none emits power or more than kMaxEmissiveMedia emit, and then
    // nothing is built or looked up.
    static std::unique_ptr<EmissionLight> forScene(const RenderScene& scene,
                                                   int resolution = kEmissionGridResolution);

    // A unit direction from the world point x towards a point drawn in the emission (above),
    // with its density p_L (1/sr); tracking gives each volume's transform at the path's time.
    // Draws four numbers always. False when the point drawn is x itself.
    bool sample(const Vec3& x, TrackingContext& tracking, Sampler& sampler, Vec3* wi,
                float* pdf) const;
    // p_L(wi) from x (1/sr), wi a unit vector: 0 where the ray meets no emitting cell.
    float pdf(const Vec3& x, const Vec3& wi, TrackingContext& tracking) const;

    // A distance along a ray (a unit direction) over (0, tEnd) drawn ∝ the emitted power per
    // volume of the cells it crosses, plus, where `floor`, a floor over each emissive medium's
    // bounds (above; the line sample's, whose estimate needs a density wherever anything glows).
    // Without it only the cells that emit are drawn from (a flight's point,
    // render/flight_emission.h, whose collisions find the rest), and a ray that misses their
    // box walks nothing. The point t, its density pdf (1/m), and the line's mass, the integral
    // of the unnormalised density over (0, tEnd) (1/m², world) that distancePdf divides by.
    struct LinePoint {
        float t = 0.f, pdf = 0.f, mass = 0.f;
    };
    // One number. False where the ray meets nothing to draw from before tEnd (then it meets no
    // emission that the table holds either).
    bool sampleDistance(const Ray& ray, float tEnd, TrackingContext& tracking, float u, bool floor,
                        LinePoint* point) const;
    // The density sampleDistance draws the distance t along ray with (1/m), given the line's
    // mass: the media overlapping at t add theirs.
    float distancePdf(const Ray& ray, float t, float mass, bool floor,
                      TrackingContext& tracking) const;

    double power() const { return mPower; }         // W over 360–830 nm, the table's
    size_t cells() const { return mCells.size(); }  // cells that emit

private:
    // One medium's grid: per cell P_c / (P V_c,object) (1/m³), walked by the majorant's DDA;
    // the floor of its distance density (1/m³, object space); the box of the cells that emit
    // (object space), beyond which the power is 0.
    struct Grid {
        size_t medium;
        MajorantGrid density;
        float floor = 0.f;
        Bounds3 glow;
    };
    struct CellRef {
        uint32_t grid, cell;  // cell: index in the order of MajorantGrid::cell()
    };
    EmissionLight() = default;
    // Calls f(t0, t1, density, grid) for each span of ray over (0, tEnd) in a cell of each grid
    // in turn, density the distance sampler's per world volume (1/m³) with or without its
    // floor, until f returns false; without the floor only the spans in the box that glows.
    template <typename F>
    void walkLine(const Ray& ray, float tEnd, TrackingContext& tracking, bool floor, F&& f) const;
    // Medium `index`'s cells' power (W), summed from its photon emitter's table, appended to
    // mGrids (with no density yet) when it emits.
    std::vector<double> addMedium(size_t index, const Medium& medium, int resolution);
    // The distance sampler's density per world volume (1/m³) at the world point p, with or
    // without its floor, over every grid but `skip`.
    float densityAt(const Vec3& p, TrackingContext& tracking, bool floor, size_t skip) const;

    std::vector<Grid> mGrids;
    std::vector<CellRef> mCells;  // the cells that emit
    std::vector<double> mCdf;     // their cumulative power, then normalised to end at 1
    double mPower = 0.0;
};

}  // namespace mirage
