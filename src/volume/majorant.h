// Majorant grid: a coarse uniform grid over a medium's object-space bounds holding, per cell,
// an upper bound of σt (1/m) over the cell. Delta tracking and ratio tracking walk it with a
// 3D-DDA, so that tentative collisions are dense only where the medium is dense (the same idea
// as pbrt-v4's MajorantGrid).
#pragma once

#include <functional>
#include <vector>

#include "core/math.h"
#include "core/progress.h"
#include "volume/grid.h"
#include "volume/vector_grid.h"

namespace mirage {

class MajorantGrid {
public:
    MajorantGrid() = default;
    // A grid of res³ cells at most over `bounds` (object space); cells are cubes-ish.
    MajorantGrid(const Bounds3& bounds, int maxRes);

    // Adds scale × (max of `grid` over each cell, including the trilinear footprint of the
    // voxels that touch it) to every cell. Call once per medium component.
    void addGrid(const FloatGrid& grid, float scale);
    // Adds f(max of `grid` over each cell) for a non-decreasing f: a component whose σ is a
    // monotone but non-linear function of its grid value (chlorophyll's A·C^(1−B)).
    void addGridMonotone(const FloatGrid& grid, const std::function<float(float)>& f);
    // Adds a constant (homogeneous component) over the whole bounds.
    void addConstant(float value);
    // Adds one value per cell, in the order of cell(): a table over the same cells walked by
    // the same DDA (render/emission_light.h: emitted power per volume, not σt).
    void addCells(const std::vector<float>& values);
    // Replaces each cell c by the maximum over the cells within reach[c] of it (metres per
    // axis, one entry per cell in the order of cell()). A point of c
    // moved by at most reach[c] lands there, so this bounds f(x − d(x)) when |d_a(x)| ≤
    // reach[c]_a for every x in c: the displacement depends on the velocity where x is.
    void dilateLocally(const std::vector<Vec3>& reach);
    // Per cell, the largest |v_a| a trilinear (or staggered) lookup of `velocity` can return
    // inside the cell: the maximum over the stored vectors whose stencil reaches it.
    std::vector<Vec3> cellComponentBounds(const VectorGrid& velocity) const;

    const Bounds3& bounds() const { return mBounds; }
    int res(int axis) const { return mRes[axis]; }
    Vec3 cellSize() const { return mCellSize; }
    float cell(int x, int y, int z) const {
        return mValues[(size_t(z) * mRes[1] + y) * mRes[0] + x];
    }
    float maxValue() const;
    // The value of the cell holding the object-space point p (a point on a cell's face takes
    // either cell's; the walks below tell the same cells apart only up to such points), 0 outside
    // the bounds.
    float at(const Vec3& p) const;

    // Walks the cells a ray crosses in [tMin, tMax] (object-space ray; d need not be unit,
    // t is the ray parameter). Calls f(t0, t1, sigmaMaj) per segment in order; stops when f
    // returns false. Returns false if stopped early.
    template <typename F>
    bool traverse(const Vec3& o, const Vec3& d, float tMin, float tMax, F&& f) const;

    // The same walk, resumable: next() gives the segment from where the walk stands to the end
    // of its cell and moves nothing; advanceTo(t) moves the walk along it. Free-flight sampling
    // keeps one across the tentative collisions of a flight, so each collision costs a step in
    // its cell instead of a new walk from the collision (its set-up is ~4× a cell's step).
    class Walk;

private:
    friend class Walk;
    // Per cell: the max of `grid` over the cell and the trilinear footprint of its voxels.
    std::vector<float> cellMaxima(const FloatGrid& grid) const;
    template <typename Grid>  // a NanoVDB grid at any precision (majorant.cpp)
    std::vector<float> cellMaximaOf(const Grid& grid, Progress& progress) const;

    Bounds3 mBounds;
    int mRes[3] = {0, 0, 0};
    Vec3 mCellSize;
    std::vector<float> mValues;
};

class MajorantGrid::Walk {
public:
    struct Segment {
        float t0, t1, sigmaMaj;
    };
    Walk() = default;
    // Walks the cells of grid that the ray o + t d crosses in [tMin, tMax] (object space).
    Walk(const MajorantGrid& grid, const Vec3& o, const Vec3& d, float tMin, float tMax);
    // The next non-empty segment: [where the walk stands, the end of its cell or tMax]. False
    // when the walk has reached tMax or left the bounds.
    bool next(Segment* s);
    // Whether nothing is left to walk (a ray that missed the bounds has nothing from the start).
    bool done() const { return mValues == nullptr; }
    // Moves the walk to t within the segment next() gave (t = its t1 finishes the cell).
    void advanceTo(float t) { mT = t; }

private:
    // Left uninitialised but for mValues: a tracker keeps one per medium on the stack.
    const float* mValues = nullptr;  // null: nothing left to walk
    float mO[3], mLo[3], mCellSize[3];
    int mCell[3], mStep[3], mStop[3];
    long mStride[3], mIndex;
    float mTNext[3], mInvD[3];
    float mT, mTEnd;
    bool mLastCell;  // rounding put the last boundary before tMax: this cell runs to it
};

}  // namespace mirage

#include "volume/majorant_traverse.inl"
