#include "volume/majorant.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "core/error.h"
#include "volume/grid_lookup.h"
#include "volume/index_map.h"
#include "volume/load_progress.h"
#include "volume/stored_values.h"

namespace mirage {

MajorantGrid::MajorantGrid(const Bounds3& bounds, int maxRes) : mBounds(bounds) {
    MIRAGE_CHECK(maxRes >= 1);
    if (bounds.empty()) return;
    // Cells roughly cubic: the longest axis gets maxRes cells of edge h, the others as many
    // cells of about the same edge as fit (at least one). Each axis is then divided exactly,
    // so the cells tile the bounds with no remainder.
    const Vec3 diag = bounds.diagonal();
    const float longest = std::max(diag.x, std::max(diag.y, diag.z));
    const float h = longest / float(maxRes);
    for (int a = 0; a < 3; ++a) {
        int n = h > 0.f ? int(std::ceil(diag[a] / h - 1e-3f)) : 1;
        mRes[a] = clamp(n, 1, maxRes);
        mCellSize[a] = diag[a] / float(mRes[a]);
    }
    mValues.assign(size_t(mRes[0]) * mRes[1] * mRes[2], 0.f);
}

void MajorantGrid::addConstant(float value) {
    MIRAGE_CHECK(value >= 0.f);
    for (float& v : mValues) v += value;
}

void MajorantGrid::addCells(const std::vector<float>& values) {
    MIRAGE_CHECK(values.size() == mValues.size());
    for (size_t i = 0; i < values.size(); ++i) {
        MIRAGE_CHECK(values[i] >= 0.f);
        mValues[i] += values[i];
    }
}

void MajorantGrid::dilateLocally(const std::vector<Vec3>& reach) {
    MIRAGE_CHECK(reach.size() == mValues.size());
    const std::vector<float> still = mValues;
    for (int z = 0; z < mRes[2]; ++z)
        for (int y = 0; y < mRes[1]; ++y)
            for (int x = 0; x < mRes[0]; ++x) {
                const size_t i = (size_t(z) * mRes[1] + y) * mRes[0] + x;
                int n[3];
                for (int a = 0; a < 3; ++a) {
                    const double cells = mCellSize[a] > 0.f && reach[i][a] > 0.f
                                             ? double(reach[i][a]) / mCellSize[a] * 1.001
                                             : 0.0;
                    n[a] = int(std::min<double>(std::ceil(cells), mRes[a]));
                }
                if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
                float m = 0.f;
                for (int cz = std::max(0, z - n[2]); cz <= std::min(mRes[2] - 1, z + n[2]); ++cz)
                    for (int cy = std::max(0, y - n[1]); cy <= std::min(mRes[1] - 1, y + n[1]);
                         ++cy) {
                        const float* row = &still[(size_t(cz) * mRes[1] + cy) * mRes[0]];
                        for (int cx = std::max(0, x - n[0]); cx <= std::min(mRes[0] - 1, x + n[0]);
                             ++cx)
                            m = std::max(m, row[cx]);
                    }
                mValues[i] = m;
            }
}

std::vector<Vec3> MajorantGrid::cellComponentBounds(const VectorGrid& velocity) const {
    std::vector<Vec3> bounds(mValues.size(), Vec3(0.f));
    if (!velocity.valid() || mValues.empty()) return bounds;
    const nanovdb::Vec3fGrid& g = *velocity.grid();
    // A stored vector at index position q reaches lookups within one voxel of q (trilinear);
    // a staggered component sits half a voxel off its voxel, so 1.5 voxels on its own axis.
    // One box per block of voxels (a leaf, or a tile), padded a thousandth of a voxel for the
    // rounding of the world → index map, as the scalar splats are.
    const double reach = (velocity.staggered() ? 1.5 : 1.0) + 1e-3;
    auto splat = [&](const nanovdb::Coord& origin, int dim, const Vec3& m) {
        if (!(m.x > 0.f || m.y > 0.f || m.z > 0.f)) return;
        Bounds3 box;
        for (int c = 0; c < 8; ++c) {
            nanovdb::Vec3d corner;
            for (int a = 0; a < 3; ++a)
                corner[a] = c & (1 << a) ? double(origin[a]) + (dim - 1) + reach
                                         : double(origin[a]) - reach;
            const nanovdb::Vec3d p = g.indexToWorld(corner);
            box.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            if (box.hi[a] < mBounds.lo[a] || box.lo[a] > mBounds.hi[a]) return;
            auto cellOf = [&](float v) {
                const float c = (v - mBounds.lo[a]) / mCellSize[a];
                if (!(c > 0.f)) return 0;
                return c >= float(mRes[a]) ? mRes[a] - 1 : int(c);
            };
            lo[a] = cellOf(box.lo[a]);
            hi[a] = cellOf(box.hi[a]);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) {
                    Vec3& b = bounds[(size_t(z) * mRes[1] + y) * mRes[0] + x];
                    b = vmax(b, m);
                }
    };
    auto absMax = [](const nanovdb::Vec3f& v, Vec3* m) {
        *m = vmax(*m, Vec3(std::abs(v[0]), std::abs(v[1]), std::abs(v[2])));
    };
    const auto& tree = g.tree();
    const auto* leaf = tree.getFirstLeaf();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i) {
        Vec3 m(0.f);
        for (const auto& v : leaf[i].data()->mValues) absMax(v, &m);
        splat(leaf[i].origin(), 8, m);
    }
    const auto* lower = tree.getFirstLower();
    for (uint32_t i = 0; i < tree.nodeCount(1); ++i)
        for (uint32_t n = 0; n < 4096; ++n)
            if (!lower[i].data()->isChild(n)) {
                Vec3 m(0.f);
                absMax(lower[i].data()->mTable[n].value, &m);
                splat(lower[i].offsetToGlobalCoord(n), 8, m);
            }
    const auto* upper = tree.getFirstUpper();
    for (uint32_t i = 0; i < tree.nodeCount(2); ++i)
        for (uint32_t n = 0; n < 32768; ++n)
            if (!upper[i].data()->isChild(n)) {
                Vec3 m(0.f);
                absMax(upper[i].data()->mTable[n].value, &m);
                splat(upper[i].offsetToGlobalCoord(n), 128, m);
            }
    const auto* root = tree.root().data();
    for (uint32_t t = 0; t < root->mTableSize; ++t)
        if (!root->tile(t)->isChild()) {
            Vec3 m(0.f);
            absMax(root->tile(t)->value, &m);
            splat(root->tile(t)->origin(), 4096, m);
        }
    return bounds;
}

float MajorantGrid::at(const Vec3& p) const {
    if (mValues.empty() || !mBounds.contains(p)) return 0.f;
    int c[3];
    for (int a = 0; a < 3; ++a)
        c[a] = std::min(int((p[a] - mBounds.lo[a]) / mCellSize[a]), mRes[a] - 1);
    return cell(c[0], c[1], c[2]);
}

float MajorantGrid::maxValue() const {
    float m = 0.f;
    for (float v : mValues) m = std::max(m, v);
    return m;
}

namespace {

// The cells each index coordinate's footprint touches along one axis, from coordinate `first`.
struct AxisCells {
    int32_t first = 0;
    std::vector<int> lo, hi;
};

// Splats values onto the cells their trilinear footprint touches. A block of voxels (leaf or
// tile) covering index coordinates [lo, hi] (inclusive) influences lookups in the open box
// (lo - 1, hi + 1); that box, mapped to object space by the grid's affine map, bounds the
// object-space region where any of its values can appear in a lookup.
template <typename Grid>
class Splatter {
public:
    Splatter(const Grid& grid, const Bounds3& bounds, const int res[3], const Vec3& cellSize,
             std::vector<float>& cells)
        : mGrid(grid), mBounds(bounds), mCells(cells) {
        for (int a = 0; a < 3; ++a) {
            mRes[a] = res[a];
            mInvCell[a] = cellSize[a] > 0.f ? 1.f / cellSize[a] : 0.f;
        }
    }

    void splat(const nanovdb::Coord& origin, int dim, float value) {
        if (!(value > 0.f)) return;
        // The footprint, widened by a thousandth of a voxel so that float rounding in the
        // sampler's world → index map cannot place a lookup just outside it.
        constexpr double kPad = 1.001;
        Bounds3 box;
        for (int c = 0; c < 8; ++c) {
            nanovdb::Vec3d corner;
            for (int a = 0; a < 3; ++a)
                corner[a] =
                    c & (1 << a) ? double(origin[a]) + (dim - 1) + kPad : double(origin[a]) - kPad;
            nanovdb::Vec3d p = mGrid.indexToWorld(corner);
            box.expand(Vec3(float(p[0]), float(p[1]), float(p[2])));
        }
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            if (box.hi[a] < mBounds.lo[a] || box.lo[a] > mBounds.hi[a]) return;
            lo[a] = cellIndex(a, box.lo[a]);
            hi[a] = cellIndex(a, box.hi[a]);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y) {
                float* row = &mCells[(size_t(z) * mRes[1] + y) * mRes[0]];
                for (int x = lo[0]; x <= hi[0]; ++x) row[x] = std::max(row[x], value);
            }
    }

    // A leaf voxel by voxel: each value onto the cells its own footprint (x − 1, x + 1) touches,
    // instead of the leaf's maximum onto every cell the leaf's footprint touches. Cells of a few
    // voxels then hold the maximum of the voxels near them, not of the whole 8³ leaf: in a wispy
    // smoke most cells are far below their leaf's maximum. Needs an axis-aligned index map
    // (then each axis maps on its own); false, and nothing splatted, otherwise.
    bool splatVoxels(const nanovdb::Coord& origin, const float* values) {
        if (!axisAligned()) return false;
        int lo[3][8], hi[3][8];
        for (int a = 0; a < 3; ++a)
            for (int l = 0; l < 8; ++l) {
                const int32_t i = origin[a] + l;
                const AxisCells* t = mTable ? &(*mTable)[a] : nullptr;
                if (t && i >= t->first && size_t(i - t->first) < t->lo.size()) {
                    lo[a][l] = t->lo[size_t(i - t->first)];
                    hi[a][l] = t->hi[size_t(i - t->first)];
                } else {
                    voxelCells(a, i, &lo[a][l], &hi[a][l]);
                }
            }
        // Voxels whose footprints touch the same cells on every axis share their splat: per
        // axis, the runs of coordinates with the same cell range, and per box of runs, one
        // splat of the box's maximum. The cells get the same maxima as one splat per voxel (a
        // maximum in any order), for a pass over the values and a few splats per leaf.
        Run runs[3][8];
        int count[3];
        for (int a = 0; a < 3; ++a) count[a] = sameCellRuns(lo[a], hi[a], runs[a]);
        for (int i = 0; i < count[0]; ++i)
            for (int j = 0; j < count[1]; ++j)
                for (int k = 0; k < count[2]; ++k) {
                    const Run &rx = runs[0][i], &ry = runs[1][j], &rz = runs[2][k];
                    // NanoVDB leaf order: offset = x·64 + y·8 + z.
                    float m = 0.f;
                    for (int x = rx.first; x < rx.end; ++x)
                        for (int y = ry.first; y < ry.end; ++y)
                            for (int z = rz.first; z < rz.end; ++z) {
                                const float v = values[(x << 6) | (y << 3) | z];
                                m = v > m ? v : m;  // NaN and values ≤ 0 add nothing
                            }
                    if (m > 0.f) splatCells(rx, ry, rz, m);
                }
        return true;
    }

    // Per axis, voxelCells of every index coordinate of the leaves the grid's active box
    // touches: the map evaluated once per coordinate instead of 48 times per leaf. Empty
    // unless the map is axis-aligned.
    std::array<AxisCells, 3> cellTable() const {
        std::array<AxisCells, 3> table;
        const nanovdb::CoordBBox box = mGrid.indexBBox();
        if (!axisAligned() || box.empty()) return table;
        for (int a = 0; a < 3; ++a) {
            AxisCells& t = table[size_t(a)];
            t.first = box.min()[a] & ~7;
            const size_t n = size_t(int64_t(box.max()[a] | 7) - t.first + 1);
            t.lo.resize(n);
            t.hi.resize(n);
            for (size_t k = 0; k < n; ++k) voxelCells(a, t.first + int32_t(k), &t.lo[k], &t.hi[k]);
        }
        return table;
    }
    // Splats from the table (the same for every thread's splatter); null: the map each time.
    void useTable(const std::array<AxisCells, 3>* table) { mTable = table; }

private:
    // The cells [*lo, *hi] on axis a that voxel coordinate i's footprint (i − 1.001, i + 1.001)
    // touches (axis-aligned map); *hi < *lo when it lies entirely outside the bounds.
    void voxelCells(int a, int32_t i, int* lo, int* hi) const {
        constexpr double kPad = 1.001;
        const double w0 = axisToWorld(a, double(i) - kPad), w1 = axisToWorld(a, double(i) + kPad);
        *lo = cellIndex(a, float(std::min(w0, w1)));
        *hi = cellIndex(a, float(std::max(w0, w1)));
        if (std::max(w0, w1) < double(mBounds.lo[a]) || std::min(w0, w1) > double(mBounds.hi[a]))
            *hi = *lo - 1;
    }

    // Coordinates [first, end) of a leaf on one axis whose footprints touch cells [lo, hi].
    struct Run {
        int first, end, lo, hi;
    };
    // The runs of equal cell ranges along one axis; ranges that touch no cell (hi < lo) are
    // left out. Returns their number.
    static int sameCellRuns(const int lo[8], const int hi[8], Run runs[8]) {
        int n = 0;
        for (int l = 0; l < 8; ++l) {
            if (hi[l] < lo[l]) continue;
            if (n > 0 && runs[n - 1].end == l && runs[n - 1].lo == lo[l] && runs[n - 1].hi == hi[l])
                ++runs[n - 1].end;
            else
                runs[n++] = Run{l, l + 1, lo[l], hi[l]};
        }
        return n;
    }
    void splatCells(const Run& x, const Run& y, const Run& z, float v) {
        for (int cz = z.lo; cz <= z.hi; ++cz)
            for (int cy = y.lo; cy <= y.hi; ++cy) {
                float* row = &mCells[(size_t(cz) * mRes[1] + cy) * mRes[0]];
                for (int cx = x.lo; cx <= x.hi; ++cx) row[cx] = std::max(row[cx], v);
            }
    }

    bool axisAligned() const { return isDiagonal3x3(mGrid.map().mMatD); }
    // The world coordinate on axis a of index coordinate i on that axis (axis-aligned map).
    double axisToWorld(int a, double i) const {
        nanovdb::Vec3d p(0.0);
        p[a] = i;
        return mGrid.indexToWorld(p)[a];
    }
    int cellIndex(int a, float x) const {
        float c = (x - mBounds.lo[a]) * mInvCell[a];
        if (!(c > 0.f)) return 0;
        return c >= float(mRes[a]) ? mRes[a] - 1 : int(c);
    }

    const Grid& mGrid;
    const Bounds3& mBounds;
    const std::array<AxisCells, 3>* mTable = nullptr;
    std::vector<float>& mCells;
    int mRes[3];
    float mInvCell[3];
};

}  // namespace

void MajorantGrid::addGrid(const FloatGrid& grid, float scale) {
    MIRAGE_CHECK(grid.valid() && scale >= 0.f);
    if (mValues.empty() || scale == 0.f) return;
    std::vector<float> cells = cellMaxima(grid);
    // The relative margin covers float rounding: a trilinear lerp of values ≤ m can come out
    // an ulp above m.
    const float margin = scale * (1.f + 1e-6f);
    for (size_t i = 0; i < mValues.size(); ++i) mValues[i] += margin * cells[i];
}

void MajorantGrid::addGridMonotone(const FloatGrid& grid, const std::function<float(float)>& f) {
    MIRAGE_CHECK(grid.valid());
    if (mValues.empty()) return;
    std::vector<float> cells = cellMaxima(grid);
    // f is non-decreasing, so f(max of the grid over a cell) bounds f over the cell; the margin
    // is on the argument, for the same trilinear rounding as above.
    for (size_t i = 0; i < mValues.size(); ++i)
        mValues[i] += std::max(0.f, f(cells[i] * (1.f + 1e-6f)));
}

std::vector<float> MajorantGrid::cellMaxima(const FloatGrid& grid) const {
    // A big grid's leaves take a second or more: a stage of its load.
    LoadStage progress("majorant of", "", "grid '" + grid.name() + "'", grid.treeBytes(),
                       grid.leafCount(), "leaves");
    return grid.visit([&](const auto& g) { return cellMaximaOf(g, progress); });
}

template <typename Grid>
std::vector<float> MajorantGrid::cellMaximaOf(const Grid& g, Progress& progress) const {
    const auto& tree = g.tree();

    // Per-cell maximum of this grid first, then added: a sum of per-component maxima bounds
    // the maximum of the sum (σt = Σ scale_i · grid_i).
    std::vector<float> cells(mValues.size(), 0.f);
    Splatter<Grid> splatter(g, mBounds, mRes, mCellSize, cells);

    // Leaves: all 512 values, inactive ones included (the sampler reads them), as a lookup
    // decodes them at a quantised precision (a bound of the floats would not bound what the
    // lookups return); voxel by voxel where the map allows, else the leaf's maximum over the
    // leaf's footprint.
    auto splatLeaf = [](Splatter<Grid>& s, const auto& leaf, float* decoded) {
        const float* v = leafValues(leaf, decoded);
        if (s.splatVoxels(leaf.origin(), v)) return;
        float m = 0.f;
        for (int k = 0; k < 512; ++k) m = std::max(m, v[k]);
        s.splat(leaf.origin(), 8, m);
    };
    const std::array<AxisCells, 3> table = splatter.cellTable();
    splatter.useTable(&table);
    constexpr size_t kParallelCells = size_t(1) << 24;
    if constexpr (!std::is_same_v<typename Grid::BuildType, nanovdb::FpN>) {
        // Leaves of one size, indexed from the first: in parallel, each thread onto cells of
        // its own, merged by maximum: exact, so the same cells for any thread count. A fine
        // majorant grid (over kParallelCells cells) is splatted by one thread.
        const auto* leaf = tree.getFirstLeaf();
        auto splatLeaves = [&](Splatter<Grid>& s, uint32_t begin, uint32_t end) {
            float decoded[512];
            for (uint32_t i = begin; i < end; ++i) splatLeaf(s, leaf[i], decoded);
        };
        if (cells.size() > kParallelCells) {
            splatLeaves(splatter, 0, tree.nodeCount(0));
        } else {
            tbb::enumerable_thread_specific<std::vector<float>> own(
                [&] { return std::vector<float>(cells.size(), 0.f); });
            tbb::parallel_for(tbb::blocked_range<uint32_t>(0, tree.nodeCount(0), 256),
                              [&](const tbb::blocked_range<uint32_t>& r) {
                                  Splatter<Grid> s(g, mBounds, mRes, mCellSize, own.local());
                                  s.useTable(&table);
                                  splatLeaves(s, r.begin(), r.end());
                                  progress.advance(r.size());
                              });
            for (const std::vector<float>& o : own)
                for (size_t c = 0; c < cells.size(); ++c) cells[c] = std::max(cells[c], o[c]);
        }
    } else {
        // FpN leaves vary in size: one thread, through their lower nodes (stored_values.h).
        float decoded[512];
        forEachLeaf(tree, [&](const auto& leaf) { splatLeaf(splatter, leaf, decoded); });
    }
    // Tiles of the lower (8³-voxel tiles) and upper (128³) internal nodes and of the root
    // (4096³). Inactive tiles count too: their value is what a lookup there returns.
    const auto* lower = tree.getFirstLower();
    for (uint32_t i = 0; i < tree.nodeCount(1); ++i) {
        const auto& node = lower[i];
        for (uint32_t n = 0; n < 4096; ++n)
            if (!node.data()->isChild(n))
                splatter.splat(node.offsetToGlobalCoord(n), 8, node.data()->mTable[n].value);
    }
    const auto* upper = tree.getFirstUpper();
    for (uint32_t i = 0; i < tree.nodeCount(2); ++i) {
        const auto& node = upper[i];
        for (uint32_t n = 0; n < 32768; ++n)
            if (!node.data()->isChild(n))
                splatter.splat(node.offsetToGlobalCoord(n), 128, node.data()->mTable[n].value);
    }
    const auto* root = tree.root().data();
    for (uint32_t t = 0; t < root->mTableSize; ++t) {
        const auto* tile = root->tile(t);
        if (!tile->isChild()) splatter.splat(tile->origin(), 4096, tile->value);
    }
    // Outside every tile a lookup returns the background (0 for a loaded fog volume).
    const float background = std::max(0.f, tree.background());
    for (float& c : cells) c = std::max(c, background);
    return cells;
}

}  // namespace mirage
