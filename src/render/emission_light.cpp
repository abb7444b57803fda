#include "render/emission_light.h"

#include <algorithm>
#include <cmath>

#include "photon/medium_emitter.h"

namespace mirage {

namespace {

// Adds `power`, spread uniformly over the object-space box centre ± size/2, to the cells of g
// it overlaps, in proportion to the overlap (index order of MajorantGrid::cell()); a box
// beyond the bounds gives its outside part to the cells at the edge.
void splat(const MajorantGrid& g, const Vec3& centre, const Vec3& size, double power,
           std::vector<double>* cells) {
    int lo[3], hi[3];
    float a0[3], a1[3];  // the box's extent in cell units along each axis
    for (int a = 0; a < 3; ++a) {
        const float h = g.cellSize()[a], n = float(g.res(a));
        a0[a] = std::clamp((centre[a] - 0.5f * size[a] - g.bounds().lo[a]) / h, 0.f, n);
        a1[a] = std::clamp((centre[a] + 0.5f * size[a] - g.bounds().lo[a]) / h, 0.f, n);
        if (!(a1[a] > a0[a])) {  // outside, or flat: all in the nearest cell
            a0[a] = std::min(a0[a], n - 0.5f);
            a1[a] = a0[a] + 1e-3f;
        }
        lo[a] = std::min(int(a0[a]), g.res(a) - 1);
        hi[a] = std::min(int(a1[a]), g.res(a) - 1);
    }
    auto overlap = [&](int a, int c) {
        return std::max(0.f, std::min(a1[a], float(c + 1)) - std::max(a0[a], float(c))) /
               (a1[a] - a0[a]);
    };
    for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x)
                (*cells)[(size_t(z) * size_t(g.res(1)) + size_t(y)) * size_t(g.res(0)) +
                         size_t(x)] +=
                    power * double(overlap(0, x) * overlap(1, y) * overlap(2, z));
}

float cellVolume(const MajorantGrid& g) {
    const Vec3 h = g.cellSize();
    return h.x * h.y * h.z;
}

// |det| of the volume's linear map at the path's time: world volume per object volume.
float volumeScale(const Medium::Context& ctx) {
    return float(std::abs(ctx.objectToWorld().linear.determinant()));
}

// The object-space box of g's cells whose value is > 0.
Bounds3 glowBox(const MajorantGrid& g, const std::vector<float>& values) {
    Bounds3 box;
    const Vec3 h = g.cellSize();
    for (int z = 0, c = 0; z < g.res(2); ++z)
        for (int y = 0; y < g.res(1); ++y)
            for (int x = 0; x < g.res(0); ++x, ++c) {
                if (!(values[size_t(c)] > 0.f)) continue;
                const Vec3 lo(g.bounds().lo.x + float(x) * h.x, g.bounds().lo.y + float(y) * h.y,
                              g.bounds().lo.z + float(z) * h.z);
                box.expand(lo);
                box.expand(lo + h);
            }
    return box;
}

}  // namespace

std::vector<double> EmissionLight::addMedium(size_t index, const Medium& medium, int resolution) {
    const MediumEmitter emitter(medium);
    if (!(emitter.tablePower() > 0.0)) return {};
    Grid grid{index, MajorantGrid(medium.objectBounds(), resolution), 0.f, Bounds3()};
    const int n = grid.density.res(0) * grid.density.res(1) * grid.density.res(2);
    std::vector<double> power(size_t(n), 0.0);
    const Vec3 size = emitter.cellSize();
    for (const MediumEmitter::CellPower& c : emitter.cellPowers())
        splat(grid.density, c.centre, size, c.power, &power);
    mGrids.push_back(std::move(grid));
    return power;
}

std::unique_ptr<EmissionLight> EmissionLight::forScene(const RenderScene& scene, int resolution) {
    size_t emissive = 0;
    for (const auto& m : scene.media) emissive += m->emissive() ? 1 : 0;
    if (emissive > kMaxEmissiveMedia) return nullptr;
    std::unique_ptr<EmissionLight> light(new EmissionLight());
    std::vector<std::vector<double>> powers;
    for (size_t i = 0; i < scene.media.size(); ++i) {
        const Medium& m = *scene.media[i];
        if (!m.emissive() || m.homogeneous()) continue;
        std::vector<double> p = light->addMedium(i, m, resolution);
        if (!p.empty()) powers.push_back(std::move(p));
    }
    // The cells that emit, in order of medium and cell: the same table for any thread count.
    for (size_t g = 0; g < powers.size(); ++g)
        for (size_t c = 0; c < powers[g].size(); ++c) {
            if (!(powers[g][c] > 0.0)) continue;
            light->mPower += powers[g][c];
            light->mCells.push_back({uint32_t(g), uint32_t(c)});
            light->mCdf.push_back(light->mPower);
        }
    if (!(light->mPower > 0.0)) return nullptr;
    for (double& c : light->mCdf) c /= light->mPower;
    for (size_t g = 0; g < powers.size(); ++g) {
        Grid& grid = light->mGrids[g];
        const double perCell = light->mPower * double(cellVolume(grid.density));
        std::vector<float> values(powers[g].size());
        double emitting = 0.0, sum = 0.0;  // the cells that emit: their count, Σ density
        for (size_t c = 0; c < values.size(); ++c) {
            values[c] = float(powers[g][c] / perCell);
            if (values[c] > 0.f) emitting += 1.0;
            sum += double(values[c]);
        }
        grid.density.addCells(values);
        grid.floor = float(double(kDistanceFloor) * sum / emitting);
        grid.glow = glowBox(grid.density, values);
    }
    return light;
}

bool EmissionLight::sample(const Vec3& x, TrackingContext& tracking, Sampler& sampler, Vec3* wi,
                           float* pdfOut) const {
    const double u = double(sampler.get1D());
    const float u1 = sampler.get1D(), u2 = sampler.get1D(), u3 = sampler.get1D();
    const size_t k = std::min(size_t(std::upper_bound(mCdf.begin(), mCdf.end(), u) - mCdf.begin()),
                              mCells.size() - 1);
    const Grid& grid = mGrids[mCells[k].grid];
    const MajorantGrid& g = grid.density;
    const uint32_t cell = mCells[k].cell;
    const uint32_t nx = uint32_t(g.res(0)), ny = uint32_t(g.res(1));
    const Vec3 index(float(cell % nx) + u1, float((cell / nx) % ny) + u2,
                     float(cell / (nx * ny)) + u3);
    const Vec3 h = g.cellSize();
    const Vec3 pObject(g.bounds().lo.x + index.x * h.x, g.bounds().lo.y + index.y * h.y,
                       g.bounds().lo.z + index.z * h.z);
    const Vec3 y = tracking.context(grid.medium).objectToWorld().point(pObject);
    const Vec3 d = y - x;
    const float len = length(d);
    if (!(len > 0.f)) return false;
    *wi = d / len;
    *pdfOut = pdf(x, *wi, tracking);
    return *pdfOut > 0.f;
}

float EmissionLight::pdf(const Vec3& x, const Vec3& wi, TrackingContext& tracking) const {
    float sum = 0.f;
    for (const Grid& grid : mGrids) {
        const Medium::Context& ctx = tracking.context(grid.medium);
        const Transform& w2o = ctx.worldToObject();
        const Vec3 o = w2o.point(x), d = w2o.vector(wi);
        float tMin, tMax;  // cells beyond the box that glows hold nothing
        if (grid.glow.empty() || !grid.glow.intersect(o, d, 0.f, kInfinity, &tMin, &tMax))
            continue;
        float part = 0.f;
        // ∫ t² dt over each cell's span, (t1³ − t0³)/3 in a form that keeps its digits.
        grid.density.traverse(o, d, tMin, tMax, [&](float t0, float t1, float density) {
            part += density * (t1 - t0) * (t1 * t1 + t1 * t0 + t0 * t0);
            return true;
        });
        sum += part / (3.f * volumeScale(ctx));
    }
    return sum;
}

template <typename F>
void EmissionLight::walkLine(const Ray& ray, float tEnd, TrackingContext& tracking, bool floor,
                             F&& f) const {
    for (size_t g = 0; g < mGrids.size(); ++g) {
        const Grid& grid = mGrids[g];
        const Medium::Context& ctx = tracking.context(grid.medium);
        const Ray r = ctx.toObject(ray);
        float tMin = 0.f, tMax = tEnd;
        if (!floor &&
            (grid.glow.empty() || !grid.glow.intersect(r.o, r.d, 0.f, tEnd, &tMin, &tMax)))
            continue;
        const float add = floor ? grid.floor : 0.f, perWorld = 1.f / volumeScale(ctx);
        const bool on = grid.density.traverse(r.o, r.d, tMin, tMax, [&](float t0, float t1,
                                                                        float v) {
            return f(t0, t1, (v + add) * perWorld, g);
        });
        if (!on) return;
    }
}

float EmissionLight::densityAt(const Vec3& p, TrackingContext& tracking, bool floor,
                               size_t skip) const {
    float sum = 0.f;
    for (size_t g = 0; g < mGrids.size(); ++g) {
        if (g == skip) continue;
        const Grid& grid = mGrids[g];
        const Medium::Context& ctx = tracking.context(grid.medium);
        const Vec3 q = ctx.worldToObject().point(p);
        if (grid.density.bounds().contains(q))
            sum += (grid.density.at(q) + (floor ? grid.floor : 0.f)) / volumeScale(ctx);
    }
    return sum;
}

bool EmissionLight::sampleDistance(const Ray& ray, float tEnd, TrackingContext& tracking, float u,
                                   bool floor, LinePoint* point) const {
    // One walk for the total, keeping the spans it passes (a 32-cell grid's ray crosses ≤ 96
    // cells); a line through more takes a second walk instead.
    struct Span {
        float t0, t1, density;
        size_t grid;
    };
    constexpr size_t kKeptSpans = 128;
    Span spans[kKeptSpans];
    size_t kept = 0;
    bool all = true;
    float total = 0.f;
    walkLine(ray, tEnd, tracking, floor, [&](float t0, float t1, float density, size_t g) {
        total += density * (t1 - t0);
        if (kept < kKeptSpans)
            spans[kept++] = {t0, t1, density, g};
        else
            all = false;
        return true;
    });
    if (!(total > 0.f)) return false;
    // The span where the running sum passes u × total, and the point there; rounding that
    // leaves the target past the last span takes the last span's end. Where media overlap, the
    // others' density at the point adds to the span's.
    float left = u * total, density = 0.f;
    size_t grid = 0;
    auto find = [&](float t0, float t1, float d, size_t g) {
        const float mass = d * (t1 - t0);
        point->t = t1;
        density = d;
        grid = g;
        if (left < mass) {
            point->t = t0 + left / d;
            return false;
        }
        left -= mass;
        return true;
    };
    if (all) {
        size_t i = 0;
        while (i < kept && find(spans[i].t0, spans[i].t1, spans[i].density, spans[i].grid)) ++i;
    } else {
        walkLine(ray, tEnd, tracking, floor, find);
    }
    if (mGrids.size() > 1) density += densityAt(ray.at(point->t), tracking, floor, grid);
    point->pdf = density / total;
    point->mass = total;
    return point->pdf > 0.f;
}

float EmissionLight::distancePdf(const Ray& ray, float t, float mass, bool floor,
                                 TrackingContext& tracking) const {
    return densityAt(ray.at(t), tracking, floor, mGrids.size()) / mass;
}

}  // namespace mirage
