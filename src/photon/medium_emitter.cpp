#include "photon/medium_emitter.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/sampling.h"
#include "core/spectral.h"
#include "volume/grid_lookup.h"
#include "volume/stored_values.h"

namespace mirage {

namespace {

constexpr double kFourPi = 4.0 * 3.14159265358979323846;
// Temperature step of the per-component emission integrals: at most 2 K, where linear
// interpolation of ∫ σa B dλ in T is exact to ~1e-5 (B is smooth in T).
constexpr float kMaxIntegralStepK = 2.f;
constexpr int kMaxIntegralSteps = 4096;
// Samplers every 25 K: any positive p(λ) keeps the estimate unbiased (the weight divides by it).
constexpr float kSamplerStepK = 25.f;
constexpr int kMaxSamplers = 400;

// ∫_360^830 s(λ) B(λ,T) dλ with B per nm (W·m⁻²·sr⁻¹·nm⁻¹), trapezoids at 1 nm: the spectra
// are linear between whole nanometres (spectrum.h), B is smooth at that scale.
template <typename S>
double planckIntegral(const S& s, float T) {
    double sum = 0.0;
    for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l) {
        double w = (l == int(kLambdaMin) || l == int(kLambdaMax)) ? 0.5 : 1.0;
        sum += w * double(s(float(l))) * planck(double(l), double(T)) * 1e-9;
    }
    return sum;
}

// Voxel coordinates packed into one key (21 bits per axis, offset to be non-negative).
uint64_t packCoord(int i, int j, int k) {
    constexpr int64_t kOff = 1 << 20;
    return (uint64_t(int64_t(i) + kOff) << 42) | (uint64_t(int64_t(j) + kOff) << 21) |
           uint64_t(int64_t(k) + kOff);
}
void unpackCoord(uint64_t key, int* i, int* j, int* k) {
    constexpr int64_t kOff = 1 << 20, kMask = (1 << 21) - 1;
    *i = int(int64_t((key >> 42) & kMask) - kOff);
    *j = int(int64_t((key >> 21) & kMask) - kOff);
    *k = int(int64_t(key & kMask) - kOff);
}

// Calls f(i, j, k, value) for every voxel of the grid that stores a value for which
// keep(value) holds: all 512 of each leaf (the sampler reads inactive leaf values too) and the
// voxels of lower (8³) and upper (128³) node tiles. Root tiles (4096³ voxels) are not expanded.
// Leaf values as a lookup decodes them (any precision, volume/grid_precision.h).
template <typename Grid, typename Keep, typename F>
void forEachStoredVoxel(const Grid& grid, Keep&& keep, F&& f) {
    const auto& tree = grid.tree();
    float decoded[512];
    forEachLeaf(tree, [&](const auto& leaf) {
        const nanovdb::Coord o = leaf.origin();
        const float* v = leafValues(leaf, decoded);
        for (int m = 0; m < 512; ++m)
            if (keep(v[m])) f(o[0] + ((m >> 6) & 7), o[1] + ((m >> 3) & 7), o[2] + (m & 7), v[m]);
    });
    auto tiles = [&](const auto* nodes, uint32_t count, uint32_t tableSize, int dim) {
        for (uint32_t n = 0; n < count; ++n) {
            const auto* data = nodes[n].data();
            for (uint32_t t = 0; t < tableSize; ++t) {
                if (data->isChild(t) || !keep(data->mTable[t].value)) continue;
                const nanovdb::Coord o = nodes[n].offsetToGlobalCoord(t);
                const float v = data->mTable[t].value;
                for (int a = 0; a < dim; ++a)
                    for (int b = 0; b < dim; ++b)
                        for (int c = 0; c < dim; ++c) f(o[0] + a, o[1] + b, o[2] + c, v);
            }
        }
    };
    tiles(tree.getFirstLower(), tree.nodeCount(1), 4096u, 8);
    tiles(tree.getFirstUpper(), tree.nodeCount(2), 32768u, 128);
}

}  // namespace

MediumEmitter::MediumEmitter(const Medium& medium) : mMedium(&medium) {
    const ShaderDesc& shader = medium.shader();
    MIRAGE_CHECK(shader.emission.has_value() && !medium.homogeneous());
    const EmissionSpec& e = *shader.emission;
    const FloatGrid& tgrid = medium.binding().grids()[size_t(medium.binding().temperatureSlot())];
    const float tMax =
        std::max(tgrid.maxValue() * e.temperatureScale + e.temperatureOffset, e.temperatureOffset);
    mTMin = e.minTemperature;
    if (!(tMax > mTMin) || !(e.intensity > 0.f)) return;
    tabulateIntegrals(tMax);
    tabulateSamplers(tMax);
    const std::vector<Corner> corners = emittingCorners(tgrid);
    mEmittingVoxels = corners.size();
    // A dual cell's volume in world space: the voxel's, through the volume's transform.
    const nanovdb::Vec3d h = tgrid.visit([](const auto& g) { return g.voxelSize(); });
    mCellVolume = h[0] * h[1] * h[2] * std::abs(medium.objectToWorld().linear.determinant());
    tabulateCells(corners);
}

// Per linear component, ∫ σa_c(λ) B(λ,T) dλ per unit concentration over T ∈ [mTMin, tMax]; the
// others are integrated at each point, at its concentration. The steps are independent: built
// in parallel (~600 steps of 471 Planck evaluations over a flame's 500–1730 K, ~6 ms on a core).
void MediumEmitter::tabulateIntegrals(float tMax) {
    const ShaderDesc& shader = mMedium->shader();
    int steps = std::min(kMaxIntegralSteps, int(std::ceil((tMax - mTMin) / kMaxIntegralStepK)) + 1);
    steps = std::max(steps, 2);
    mTStep = (tMax - mTMin) / float(steps - 1);
    mIntegral.resize(shader.components.size());
    for (size_t c = 0; c < shader.components.size(); ++c) {
        if (!mMedium->binding().componentModel(int(c)).linear()) continue;
        std::vector<float>& table = mIntegral[c];
        table.resize(size_t(steps));
        tbb::parallel_for(tbb::blocked_range<int>(0, steps, 16), [&](const auto& r) {
            for (int k = r.begin(); k < r.end(); ++k)
                table[size_t(k)] =
                    float(planckIntegral(shader.components[c].sigmaA, mTMin + float(k) * mTStep));
        });
    }
}

// The Planck samplers B(λ, T) v(λ) every kSamplerStepK over [mTMin, tMax].
void MediumEmitter::tabulateSamplers(float tMax) {
    const int samplers =
        std::max(2, std::min(kMaxSamplers, int(std::ceil((tMax - mTMin) / kSamplerStepK)) + 1));
    mSamplerStep = (tMax - mTMin) / float(samplers - 1);
    for (int k = 0; k < samplers; ++k) {
        const double T = double(mTMin) + double(k) * double(mSamplerStep);
        std::vector<float> dense(Spectrum::kDenseSamples);
        for (int l = 0; l < Spectrum::kDenseSamples; ++l) {
            const float lambda = kLambdaMin + float(l);
            dense[size_t(l)] =
                float(planck(double(lambda), T) * 1e-9) * SampledWavelengths::visiblePdf(lambda);
        }
        mSamplers.emplace_back(Spectrum::fromDense(std::move(dense)));
    }
}

// q at every emitting voxel centre of the temperature grid, sorted by key: the voxels found in
// order, their q (independent lookups) in parallel, the same table for any thread count. A
// sorted table, not a hash map, whose node per voxel cost ~6 ms on a 96³ fire.
std::vector<MediumEmitter::Corner> MediumEmitter::emittingCorners(const FloatGrid& tgrid) const {
    const ShaderDesc& shader = mMedium->shader();
    const EmissionSpec& e = *shader.emission;
    // Cell keys hold 21 bits per axis (packCoord): refuse a grid whose hot voxels lie beyond.
    const nanovdb::CoordBBox box = tgrid.indexBounds();
    for (int a = 0; a < 3; ++a)
        if (std::abs(box.min()[a]) >= (1 << 20) - 16 || std::abs(box.max()[a]) >= (1 << 20) - 16)
            throw MirageError("temperature grid '" + tgrid.name() +
                              "': index coordinates beyond ±1048560 voxels; the emitter of "
                              "shader '" +
                              shader.name + "' expects smaller indices");
    struct HotVoxel {
        int i, j, k;
        float T;
        Vec3 p;  // object space
    };
    std::vector<HotVoxel> voxels;
    auto hot = [&](float v) { return v * e.temperatureScale + e.temperatureOffset > mTMin; };
    tgrid.visit([&](const auto& g) {
        forEachStoredVoxel(g, hot, [&](int i, int j, int k, float v) {
            const nanovdb::Vec3f p = g.indexToWorldF(nanovdb::Vec3f(float(i), float(j), float(k)));
            voxels.push_back({i, j, k, v * e.temperatureScale + e.temperatureOffset,
                              Vec3(p[0], p[1], p[2])});
        });
    });
    std::vector<double> q(voxels.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, voxels.size(), 1024), [&](const auto& r) {
        std::vector<FloatGrid::Accessor> acc;
        for (const auto& grid : mMedium->binding().grids()) acc.push_back(grid.accessor());
        for (size_t n = r.begin(); n < r.end(); ++n) q[n] = powerDensityAt(voxels[n].p, acc);
    });
    std::vector<Corner> corners;
    for (size_t n = 0; n < voxels.size(); ++n) {
        const HotVoxel& v = voxels[n];
        if (q[n] > 0.0) corners.push_back({packCoord(v.i, v.j, v.k), float(q[n]), v.T});
    }
    std::sort(corners.begin(), corners.end(),
              [](const Corner& a, const Corner& b) { return a.key < b.key; });
    return corners;
}

// The dual cells with an emitting corner, in key order: each from its corners (in parallel),
// then the cumulative power in that order.
void MediumEmitter::tabulateCells(const std::vector<Corner>& corners) {
    std::vector<uint64_t> keys;
    keys.reserve(8 * corners.size());
    for (const Corner& c : corners) {
        int i, j, k;
        unpackCoord(c.key, &i, &j, &k);
        for (int d = 0; d < 8; ++d)
            keys.push_back(packCoord(i - (d & 1), j - ((d >> 1) & 1), k - ((d >> 2) & 1)));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    auto corner = [&](uint64_t key) -> const Corner* {
        auto it = std::lower_bound(corners.begin(), corners.end(), key,
                                   [](const Corner& c, uint64_t k) { return c.key < k; });
        return it != corners.end() && it->key == key ? &*it : nullptr;
    };
    mCells.resize(keys.size());
    std::vector<double> sums(keys.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, keys.size(), 1024), [&](const auto& r) {
        for (size_t n = r.begin(); n < r.end(); ++n) {
            Cell& cell = mCells[n];
            unpackCoord(keys[n], &cell.i, &cell.j, &cell.k);
            double sum = 0.0;
            float hottest = mTMin;
            for (int d = 0; d < 8; ++d) {
                const Corner* c = corner(packCoord(cell.i + (d & 1), cell.j + ((d >> 1) & 1),
                                                   cell.k + ((d >> 2) & 1)));
                if (!c) continue;
                sum += c->q;
                hottest = std::max(hottest, c->T);
            }
            cell.sampler = uint16_t(samplerIndex(hottest));
            sums[n] = sum;
        }
    });
    mCdf.reserve(keys.size());
    for (double sum : sums) {
        mTotal += mCellVolume * sum / 8.0;
        mCdf.push_back(mTotal);
    }
}

int MediumEmitter::samplerIndex(float T) const {
    const int n = int(mSamplers.size());
    if (n <= 1) return 0;
    return std::clamp(int(std::lround((T - mTMin) / mSamplerStep)), 0, n - 1);
}

double MediumEmitter::componentIntegral(int c, float T) const {
    const std::vector<float>& table = mIntegral[size_t(c)];
    const float x = (T - mTMin) / mTStep;
    const int k = std::clamp(int(x), 0, int(table.size()) - 2);
    const float f = std::clamp(x - float(k), 0.f, 1.f);
    return double(table[size_t(k)]) * (1.0 - f) + double(table[size_t(k) + 1]) * f;
}

double MediumEmitter::powerDensity(const Vec3& pObject) const {
    std::vector<FloatGrid::Accessor> acc;
    for (const auto& grid : mMedium->binding().grids()) acc.push_back(grid.accessor());
    return powerDensityAt(pObject, acc);
}

double MediumEmitter::powerDensityAt(const Vec3& p,
                                     const std::vector<FloatGrid::Accessor>& acc) const {
    if (mSamplers.empty()) return 0.0;
    const ShaderDesc& shader = mMedium->shader();
    const EmissionSpec& e = *shader.emission;
    const auto& grids = mMedium->binding().grids();
    const size_t ts = size_t(mMedium->binding().temperatureSlot());
    const float T = grids[ts].sample(acc[ts], p) * e.temperatureScale + e.temperatureOffset;
    if (!(T > mTMin)) return 0.0;  // Medium::eval emits nothing there either
    double sum = 0.0;
    for (size_t c = 0; c < shader.components.size(); ++c) {
        const MediumComponent& comp = shader.components[c];
        const ComponentModel& model = mMedium->binding().componentModel(int(c));
        const int slot = mMedium->binding().componentSlot(int(c));
        const float v = slot < 0 ? 1.f : grids[size_t(slot)].sample(acc[size_t(slot)], p);
        const float C = comp.concentration * mMedium->binding().densityScale() * v;
        if (!(C > 0.f)) continue;
        if (model.linear()) {
            sum += double(C) * componentIntegral(int(c), T);
        } else {
            // Not linear in C: its absorption spectrum at this C, integrated here.
            std::array<float, Spectrum::kDenseSamples> sigmaA;
            model.sigmaADense(C, sigmaA.data());
            sum += planckIntegral([&](float l) { return sigmaA[size_t(l - kLambdaMin)]; }, T);
        }
    }
    return kFourPi * double(e.intensity) * sum;
}

std::vector<MediumEmitter::CellPower> MediumEmitter::cellPowers() const {
    std::vector<CellPower> out;
    out.reserve(mCells.size());
    const FloatGrid& tgrid =
        mMedium->binding().grids()[size_t(mMedium->binding().temperatureSlot())];
    tgrid.visit([&](const auto& g) {
        for (size_t i = 0; i < mCells.size(); ++i) {
            const Cell& c = mCells[i];
            const nanovdb::Vec3f p = g.indexToWorldF(
                nanovdb::Vec3f(float(c.i) + 0.5f, float(c.j) + 0.5f, float(c.k) + 0.5f));
            out.push_back({Vec3(p[0], p[1], p[2]), mCdf[i] - (i > 0 ? mCdf[i - 1] : 0.0)});
        }
    });
    return out;
}

Vec3 MediumEmitter::cellSize() const {
    const FloatGrid& tgrid =
        mMedium->binding().grids()[size_t(mMedium->binding().temperatureSlot())];
    const nanovdb::Vec3d h = tgrid.visit([](const auto& g) { return g.voxelSize(); });
    return Vec3(float(h[0]), float(h[1]), float(h[2]));
}

bool MediumEmitter::sample(Sampler& sampler, Medium::Context& ctx, PhotonEmission* out) const {
    if (mCells.empty()) return false;
    // The cell ∝ its tabulated power.
    const double target = double(sampler.get1D()) * mTotal;
    size_t i = size_t(std::upper_bound(mCdf.begin(), mCdf.end(), target) - mCdf.begin());
    i = std::min(i, mCells.size() - 1);
    const Cell& cell = mCells[i];
    const double cellPower = mCdf[i] - (i > 0 ? mCdf[i - 1] : 0.0);
    if (!(cellPower > 0.0)) return false;

    // A uniform point of the dual cell (index space maps affinely to object and world space).
    const FloatGrid& tgrid =
        mMedium->binding().grids()[size_t(mMedium->binding().temperatureSlot())];
    const float u0 = sampler.get1D(), u1 = sampler.get1D(), u2 = sampler.get1D();
    const nanovdb::Vec3f po = tgrid.visit([&](const auto& g) {
        return g.indexToWorldF(
            nanovdb::Vec3f(float(cell.i) + u0, float(cell.j) + u1, float(cell.k) + u2));
    });
    const Vec3 pObject(po[0], po[1], po[2]);

    // λ from the hottest corner's Planck spectrum times the eye's importance, then the exact
    // emission there at λ.
    float pdf = 0.f;
    const float lambda = mSamplers[cell.sampler].sample(sampler.get1D(), &pdf);
    if (!(pdf > 0.f)) return false;
    SampledWavelengths w;
    w.lambda.fill(lambda);
    w.pdf.fill(1.f);
    ctx.setWavelengths(w);
    // Motion blur: the point is drawn from the still emission, which the flow carries to
    // pObject + v·Δt at the photon's time (to first order, and with the power it had: the
    // advection of Medium::setMotion moves emission without creating it).
    const float time = ctx.timeOffset();
    const Vec3 moved = pObject + ctx.motion().displacement(pObject);
    ctx.setTimeOffset(0.f);
    MediumPoint mp;
    mMedium->eval(pObject, ctx, &mp);
    ctx.setTimeOffset(time);
    const double f = kFourPi * double(mp.sigmaA[0]) * double(mp.Le[0]);  // W·m⁻³·nm⁻¹
    out->weight = float(f * mCellVolume / (cellPower * double(pdf)));
    if (!(out->weight > 0.f) || !std::isfinite(out->weight)) return false;

    // A volume whose transform is keyed is where the photon's time places it; a keyed scale
    // changes its world volume, and the power it emits with it.
    const Transform& xf = ctx.objectToWorld();
    if (mMedium->motion().transformMoves())
        out->weight *= float(
            std::abs(xf.linear.determinant() / mMedium->objectToWorld().linear.determinant()));
    out->origin = xf.point(moved);
    out->direction = sampleUniformSphere(sampler.get1D(), sampler.get1D());
    out->lambda = lambda;
    return true;
}

}  // namespace mirage
