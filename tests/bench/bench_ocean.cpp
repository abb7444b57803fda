// Cost of the ocean shader (pure water + chlorophyll grid + CDOM: one logarithm and six
// exponentials per lookup for the non-linear chlorophyll) against a linear shader of three
// components on the same grid, per Medium::eval and per ratio-tracked transmittance ray.
// Prints medians of 5 runs, 1 thread; a program, not a test.
#include <nanovdb/util/GridBuilder.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "medium/ocean_components.h"
#include "spectrum/ocean_spectra.h"
#include "transport/tracking.h"
#include "volume/grid_lookup.h"

using namespace mirage;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// A 128³ chlorophyll field, 0.05–5 mg/m³, over a 10 m cube.
FloatGrid chlorophyllGrid() {
    nanovdb::GridBuilder<float> builder(0.f, nanovdb::GridClass::FogVolume);
    builder(
        [](const nanovdb::Coord& c) {
            return 0.05f * std::pow(100.f, c[1] / 127.f) *
                   (1.f + 0.5f * std::sin(0.1f * c[0]) * std::cos(0.13f * c[2]));
        },
        nanovdb::CoordBBox(nanovdb::Coord(0), nanovdb::Coord(127)));
    return FloatGrid(builder.getHandle<>(10.0 / 128, nanovdb::Vec3d(0.0), "chl"), "chl");
}

ShaderDesc oceanShader() {
    ShaderDesc s;
    s.name = "ocean";
    MediumComponent water, chl, cdom;
    makeWater(&water);
    chl.grid = "chl";
    makeChlorophyll(&chl);
    cdom.concentration = 0.05f;
    makeCdom(&cdom, ocean::kCdomSlope);
    s.components = {water, chl, cdom};
    return s;
}

// The same three components, all linear in the grid: the cheap path.
ShaderDesc linearShader() {
    ShaderDesc s = oceanShader();
    MediumComponent& chl = s.components[1];
    chl.kind = ComponentKind::Linear;
    chl.sigmaAExponent = Spectrum(1.f);
    chl.sigmaSExponent = 1.f;
    return s;
}

void run(const char* label, const ShaderDesc& shader) {
    Medium m(shader, {chlorophyllGrid()}, Transform(), 1.f, 64);
    Bounds3 b = m.objectBounds();
    const int n = 2000000;
    std::vector<Vec3> pts(n);
    Sampler s(1, 0, 0);
    for (auto& p : pts) p = b.lo + b.diagonal() * Vec3(s.get1D(), s.get1D(), s.get1D());
    std::vector<double> evalRates, rayRates;
    volatile float sink = 0;
    for (int r = 0; r < 5; ++r) {
        Medium::Context ctx(m);
        ctx.setWavelengths(SampledWavelengths::sampleVisible(0.3f));
        MediumPoint mp;
        auto t = Clock::now();
        float sum = 0;
        for (const auto& p : pts) {
            m.eval(p, ctx, &mp);
            sum += mp.sigmaA[0] + mp.sigmaS[3];
        }
        sink = sink + sum;
        evalRates.push_back(n / std::chrono::duration<double>(Clock::now() - t).count());

        TrackingContext tc({&m});
        const int rays = 20000;
        t = Clock::now();
        for (int i = 0; i < rays; ++i) {
            Sampler rs(2, uint64_t(i), 0);
            tc.setWavelengths(SampledWavelengths::sampleVisible(rs.get1D()));
            Vec3 o = pts[size_t(i)];
            Vec3 d = normalize(Vec3(rs.get1D() - 0.5f, rs.get1D() - 0.5f, rs.get1D() - 0.5f));
            sink = sink + transmittance(tc, Ray{o, d, kInfinity}, 20.f, rs).average();
        }
        rayRates.push_back(rays / std::chrono::duration<double>(Clock::now() - t).count());
    }
    std::printf("%-28s eval %.2f M/s, transmittance rays %.1f k/s, majorant max %.3f 1/m\n",
                label, median(evalRates) / 1e6, median(rayRates) / 1e3, m.majorant().maxValue());
}

}  // namespace

int main() {
    run("ocean (chlorophyll C^(1-B))", oceanShader());
    run("linear (same spectra)", linearShader());
    return 0;
}
