// A refractive-index field from a voxel grid of temperature (Stam & Languenou 1996:
// n = 1 + (T_p/T)(n0 − 1)) or of n itself — heat haze over a fire cache.
//
// Reconstruction: a tricubic uniform B-spline with the voxel values as control points. It is C²,
// so n is C² and ∇n is C¹: the ODE right-hand side stays continuous across voxel faces, where
// trilinear interpolation's piecewise-constant gradient jumps and makes the adaptive stepper
// crawl. The B-spline is approximating, not interpolating (it smooths each axis by the kernel
// [1 4 1]/6 at the voxel centres) and reproduces linear fields exactly. Outside the grid the
// control points take the background value, so n is constant two voxels beyond the grid.
//
// Per brick of 8³ spline cells the field keeps a bound on |∇n| from the control points (the
// derivative of a B-spline is a B-spline of the control points' differences, so the largest
// difference bounds it); where the bound is 0 the stepper runs straight chords.
#pragma once

#include <vector>

#include "medium/air_index.h"
#include "medium/index_field.h"

namespace mirage {

class FloatGrid;

// Dense samples at voxel centres: value(i, j, k) sits at origin + h·(i, j, k).
struct DenseScalarGrid {
    int nx = 0, ny = 0, nz = 0;
    double voxelSize = 1;      // h, m
    Vec3d origin;              // world position of voxel (0, 0, 0)'s centre, m
    std::vector<float> values; // x fastest
    float background = 0;      // the value everywhere outside
    float at(int i, int j, int k) const {
        if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return background;
        return values[(size_t(k) * ny + j) * nx + i];
    }
};

// The active index box of a NanoVDB grid copied into a dense grid (world transform: uniform
// scale and translation, as the loader's grids have).
DenseScalarGrid denseFromFloatGrid(const FloatGrid& grid, float background);

struct GridIndexSettings {
    enum class Quantity { Temperature, Index } quantity = Quantity::Temperature;
    // Temperature: T = offset + scale · value (K), so a fog-volume "temperature" grid whose
    // background is 0 means ambient air at `offset`.
    double temperatureOffset = 0, temperatureScale = 1;
    double tp = air::kStamTp, n0 = air::kStamN0;  // Stam & Languenou's reference
};

class GridIndexField final : public IndexField {
public:
    GridIndexField(DenseScalarGrid grid, GridIndexSettings settings);

    void eval(const Vec3d& x, double lambdaNm, double* n, Vec3d* gradient) const override;
    double gradientBound(const Vec3d& lo, const Vec3d& hi) const override;
    double straightDistance(const Vec3d& x, const Vec3d& d, double maxDistance) const override;

    static constexpr int kBrick = 8;  // spline cells per brick side

private:
    // The spline value S and its gradient (in grid units → per metre) at world x.
    void spline(const Vec3d& x, double* s, Vec3d* gradient) const;
    // |∇n| bound of brick (bi, bj, bk); 0 outside the brick grid.
    double brickBound(int bi, int bj, int bk) const;
    // Brick coordinates of world x (may be outside the brick grid).
    void brickOf(const Vec3d& x, int* b) const;

    DenseScalarGrid mGrid;
    GridIndexSettings mSettings;
    // Bricks cover spline cells [-2, n + 1) per axis (every cell whose control points touch the
    // grid): brick b holds cells kCellLo + 8b … + 7.
    static constexpr int kCellLo = -2;
    int mBricks[3] = {0, 0, 0};
    std::vector<double> mBrickBound;
};

}  // namespace mirage
