// Gridded refractive index by a tricubic B-spline (grid_index_field.h says why).
#include "medium/grid_index_field.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.h"
#include "volume/grid_lookup.h"

namespace mirage {

namespace {

// Uniform cubic B-spline basis on the cell parameter t ∈ [0, 1): weights of the control points
// c−1, c, c+1, c+2, and their derivatives d/dt.
void bsplineWeights(double t, double w[4], double dw[4]) {
    const double s = 1 - t, t2 = t * t, t3 = t2 * t;
    w[0] = s * s * s / 6;
    w[1] = (3 * t3 - 6 * t2 + 4) / 6;
    w[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
    w[3] = t3 / 6;
    dw[0] = -s * s / 2;
    dw[1] = (3 * t2 - 4 * t) / 2;
    dw[2] = (-3 * t2 + 2 * t + 1) / 2;
    dw[3] = t2 / 2;
}

// The grid's active box as a dense array, at whichever precision it holds (decoded).
template <typename Grid>
DenseScalarGrid denseFrom(const Grid& g, const std::string& name, float background) {
    const nanovdb::CoordBBox box = g.indexBBox();
    DenseScalarGrid d;
    d.nx = box.max()[0] - box.min()[0] + 1;
    d.ny = box.max()[1] - box.min()[1] + 1;
    d.nz = box.max()[2] - box.min()[2] + 1;
    const nanovdb::Vec3d vs = g.voxelSize();
    if (std::abs(vs[0] - vs[1]) > 1e-9 * vs[0] || std::abs(vs[0] - vs[2]) > 1e-9 * vs[0])
        throw MirageError(
            "grid '" + name + "': an index field needs cubic voxels (uniform scale), got " +
            std::to_string(vs[0]) + " x " + std::to_string(vs[1]) + " x " + std::to_string(vs[2]));
    d.voxelSize = vs[0];
    const nanovdb::Vec3d o =
        g.indexToWorld(nanovdb::Vec3d(box.min()[0], box.min()[1], box.min()[2]));
    d.origin = Vec3d(o[0], o[1], o[2]);
    d.background = background;
    d.values.resize(size_t(d.nx) * d.ny * d.nz);
    auto acc = g.getAccessor();
    for (int k = 0; k < d.nz; ++k)
        for (int j = 0; j < d.ny; ++j)
            for (int i = 0; i < d.nx; ++i) {
                const nanovdb::Coord c = box.min() + nanovdb::Coord(i, j, k);
                d.values[(size_t(k) * d.ny + j) * d.nx + i] =
                    acc.isActive(c) ? acc.getValue(c) : background;
            }
    return d;
}

}  // namespace

DenseScalarGrid denseFromFloatGrid(const FloatGrid& grid, float background) {
    return grid.visit([&](const auto& g) { return denseFrom(g, grid.name(), background); });
}

GridIndexField::GridIndexField(DenseScalarGrid grid, GridIndexSettings settings)
    : mGrid(std::move(grid)), mSettings(settings) {
    const bool temp = mSettings.quantity == GridIndexSettings::Quantity::Temperature;
    auto physical = [&](float v) {
        return temp ? mSettings.temperatureOffset + mSettings.temperatureScale * v : double(v);
    };
    if (!(mGrid.voxelSize > 0) || mGrid.nx <= 0 || mGrid.ny <= 0 || mGrid.nz <= 0 ||
        mGrid.values.size() != size_t(mGrid.nx) * mGrid.ny * mGrid.nz)
        throw MirageError("index field grid: expected a non-empty grid with a positive voxel size");
    // The spline is a convex combination of control points: its range is theirs.
    double lo = physical(mGrid.background), hi = lo;
    for (float v : mGrid.values) {
        lo = std::min(lo, physical(v));
        hi = std::max(hi, physical(v));
    }
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo > 0))
        throw MirageError(std::string("index field grid: expected ") +
                          (temp ? "temperatures" : "indices") +
                          " that are finite and > 0 everywhere, got a minimum of " +
                          std::to_string(lo));

    const int n[3] = {mGrid.nx, mGrid.ny, mGrid.nz};
    for (int a = 0; a < 3; ++a) mBricks[a] = (n[a] + 3 + kBrick - 1) / kBrick;
    mBrickBound.assign(size_t(mBricks[0]) * mBricks[1] * mBricks[2], 0.0);
    const double h = mGrid.voxelSize;
    for (int bk = 0; bk < mBricks[2]; ++bk)
        for (int bj = 0; bj < mBricks[1]; ++bj)
            for (int bi = 0; bi < mBricks[0]; ++bi) {
                // Control points of cells c0 … c0+7 per axis: c0−1 … c0+9.
                const int c0[3] = {kCellLo + kBrick * bi, kCellLo + kBrick * bj,
                                   kCellLo + kBrick * bk};
                double maxDiff[3] = {0, 0, 0}, minV = kInfinity, maxV = -kInfinity;
                for (int k = c0[2] - 1; k <= c0[2] + kBrick + 1; ++k)
                    for (int j = c0[1] - 1; j <= c0[1] + kBrick + 1; ++j)
                        for (int i = c0[0] - 1; i <= c0[0] + kBrick + 1; ++i) {
                            const double v = mGrid.at(i, j, k);
                            minV = std::min(minV, v);
                            maxV = std::max(maxV, v);
                            if (i <= c0[0] + kBrick)
                                maxDiff[0] = std::max(maxDiff[0], std::abs(mGrid.at(i + 1, j, k) - v));
                            if (j <= c0[1] + kBrick)
                                maxDiff[1] = std::max(maxDiff[1], std::abs(mGrid.at(i, j + 1, k) - v));
                            if (k <= c0[2] + kBrick)
                                maxDiff[2] = std::max(maxDiff[2], std::abs(mGrid.at(i, j, k + 1) - v));
                        }
                double gradS = std::sqrt(maxDiff[0] * maxDiff[0] + maxDiff[1] * maxDiff[1] +
                                         maxDiff[2] * maxDiff[2]) / h;
                if (temp) {
                    // n = 1 + Tp(n0−1)/T: |∇n| = Tp(n0−1)|∇T|/T², largest at the coldest T.
                    const double tMin = std::min(physical(float(minV)), physical(float(maxV)));
                    gradS *= std::abs(mSettings.temperatureScale) * mSettings.tp *
                             std::abs(mSettings.n0 - 1) / (tMin * tMin);
                }
                mBrickBound[(size_t(bk) * mBricks[1] + bj) * mBricks[0] + bi] = gradS;
            }
}

void GridIndexField::spline(const Vec3d& x, double* s, Vec3d* gradient) const {
    const double h = mGrid.voxelSize;
    const Vec3d u = (x - mGrid.origin) / h;
    const int n[3] = {mGrid.nx, mGrid.ny, mGrid.nz};
    int c[3];
    double w[3][4], dw[3][4];
    for (int a = 0; a < 3; ++a) {
        // Beyond cells −2 … n every control point is background: constant there.
        if (!(u[a] >= kCellLo && u[a] < n[a] + 1)) {
            *s = mGrid.background;
            *gradient = Vec3d(0.0);
            return;
        }
        c[a] = int(std::floor(u[a]));
        bsplineWeights(u[a] - c[a], w[a], dw[a]);
    }
    double v = 0, gx = 0, gy = 0, gz = 0;
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j) {
            double row = 0, rowD = 0;
            for (int i = 0; i < 4; ++i) {
                const double p = mGrid.at(c[0] - 1 + i, c[1] - 1 + j, c[2] - 1 + k);
                row += w[0][i] * p;
                rowD += dw[0][i] * p;
            }
            v += w[1][j] * w[2][k] * row;
            gx += w[1][j] * w[2][k] * rowD;
            gy += dw[1][j] * w[2][k] * row;
            gz += w[1][j] * dw[2][k] * row;
        }
    *s = v;
    *gradient = Vec3d(gx, gy, gz) / h;
}

void GridIndexField::eval(const Vec3d& x, double, double* n, Vec3d* gradient) const {
    double s;
    Vec3d gs;
    spline(x, &s, &gs);
    if (mSettings.quantity == GridIndexSettings::Quantity::Index) {
        *n = s;
        *gradient = gs;
        return;
    }
    // Stam & Languenou: n = 1 + (Tp/T)(n0 − 1), ∇n = −Tp(n0 − 1) ∇T / T².
    const double T = mSettings.temperatureOffset + mSettings.temperatureScale * s;
    const double c = mSettings.tp * (mSettings.n0 - 1);
    *n = 1 + c / T;
    *gradient = gs * (-c * mSettings.temperatureScale / (T * T));
}

void GridIndexField::brickOf(const Vec3d& x, int* b) const {
    const double size = kBrick * mGrid.voxelSize;
    for (int a = 0; a < 3; ++a) {
        const double f = (x[a] - mGrid.origin[a] - kCellLo * mGrid.voxelSize) / size;
        b[a] = int(std::floor(clamp(f, -2.0, double(mBricks[a]) + 1)));
    }
}

double GridIndexField::brickBound(int bi, int bj, int bk) const {
    if (bi < 0 || bj < 0 || bk < 0 || bi >= mBricks[0] || bj >= mBricks[1] || bk >= mBricks[2])
        return 0.0;
    return mBrickBound[(size_t(bk) * mBricks[1] + bj) * mBricks[0] + bi];
}

double GridIndexField::gradientBound(const Vec3d& lo, const Vec3d& hi) const {
    int b0[3], b1[3];
    brickOf(lo, b0);
    brickOf(hi, b1);
    double bound = 0;
    for (int k = std::max(b0[2], 0); k <= std::min(b1[2], mBricks[2] - 1); ++k)
        for (int j = std::max(b0[1], 0); j <= std::min(b1[1], mBricks[1] - 1); ++j)
            for (int i = std::max(b0[0], 0); i <= std::min(b1[0], mBricks[0] - 1); ++i)
                bound = std::max(bound, brickBound(i, j, k));
    return bound;
}

double GridIndexField::straightDistance(const Vec3d& x, const Vec3d& d, double maxDistance) const {
    // A 3D-DDA over the bricks (Amanatides & Woo 1987): add up the bricks with a zero bound
    // from x until one with a non-zero bound, the end of the brick grid (constant beyond), or
    // maxDistance.
    const double size = kBrick * mGrid.voxelSize;
    Vec3d lo, hi;
    for (int a = 0; a < 3; ++a) {
        lo[a] = mGrid.origin[a] + kCellLo * mGrid.voxelSize;
        hi[a] = lo[a] + size * mBricks[a];
    }
    // The part of the ray inside the brick grid's box.
    double t0 = 0, t1 = maxDistance;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (x[a] < lo[a] || x[a] > hi[a]) return maxDistance;
            continue;
        }
        double ta = (lo[a] - x[a]) / d[a], tb = (hi[a] - x[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (t0 >= t1) return maxDistance;  // never enters: constant n all the way
    // Brick of the first point inside, nudged off a face.
    int b[3];
    brickOf(x + d * (t0 + 1e-9 * size), b);
    int step[3];
    double tNext[3], tDelta[3];
    for (int a = 0; a < 3; ++a) {
        b[a] = std::clamp(b[a], 0, mBricks[a] - 1);
        step[a] = d[a] > 0 ? 1 : -1;
        if (d[a] == 0) {
            tNext[a] = tDelta[a] = kInfinity;
            continue;
        }
        const double face = lo[a] + size * (b[a] + (d[a] > 0 ? 1 : 0));
        tNext[a] = (face - x[a]) / d[a];
        tDelta[a] = size / std::abs(d[a]);
    }
    double t = t0;
    while (t < t1) {
        if (brickBound(b[0], b[1], b[2]) > 0) return t;
        const int a = tNext[0] < tNext[1] ? (tNext[0] < tNext[2] ? 0 : 2)
                                          : (tNext[1] < tNext[2] ? 1 : 2);
        t = tNext[a];
        tNext[a] += tDelta[a];
        b[a] += step[a];
        if (b[a] < 0 || b[a] >= mBricks[a]) return maxDistance;  // left the grid: constant
    }
    return maxDistance;
}

}  // namespace mirage
