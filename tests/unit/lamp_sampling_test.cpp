// Distances drawn towards a lamp (transport/equiangular.h, render/lamp_sampling.h): the
// equiangular sampler against its density (χ²), the spot's cone interval against a brute-force
// scan, and the path tracer's single scattering from a point light and from a spot's beam
// against quadrature, with and without the lamp's points: the same mean, and near the lamp the
// equiangular points' samples stay bounded where delta tracking's alone make fireflies.
#include "render/lamp_sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "chi_square.h"
#include "light/dome_light.h"
#include "render/light_lobes.h"
#include "test_support.h"

using namespace mirage;

TEST(Equiangular, SamplesItsDensity) {
    struct Case {
        Vec3 o, d;
        float a, b;
        Vec3 c;
    };
    const Case cases[] = {
        {Vec3(0.f), Vec3(1, 0, 0), 0.f, 4.f, Vec3(1.f, 0.02f, 0.f)},    // close pass, inside
        {Vec3(0.f), Vec3(1, 0, 0), 0.f, 4.f, Vec3(2.f, 3.f, 0.f)},      // far
        {Vec3(0.f), Vec3(0, 0, 1), 1.f, 3.f, Vec3(0.1f, 0.f, -2.f)},    // lamp behind the segment
        {Vec3(0.f), Vec3(0, 1, 0), 0.f, 1.f, Vec3(0.002f, 0.5f, 0.f)},  // 2 mm from the lamp
    };
    Sampler rng(7, 0, 0);
    for (const Case& k : cases) {
        const EquiangularSegment s(k.o, k.d, k.a, k.b, k.c);
        ASSERT_FALSE(s.empty());
        const int bins = 40, n = 200000;
        std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
        for (int i = 0; i < n; ++i) {
            const float t = s.sample(rng.get1D());
            ASSERT_GE(t, k.a);
            ASSERT_LE(t, k.b);
            observed[std::min(bins - 1, int((t - k.a) / (k.b - k.a) * bins))] += 1;
        }
        // Each bin's probability by the midpoint rule on 2000 sub-steps of the density.
        double total = 0.0;
        for (int i = 0; i < bins; ++i) {
            const double w = (k.b - k.a) / double(bins);
            double p = 0.0;
            for (int j = 0; j < 2000; ++j) p += s.pdf(float(k.a + w * (i + (j + 0.5) / 2000)));
            expected[i] = p * w / 2000;
            total += expected[i];
        }
        EXPECT_NEAR(total, 1.0, 2e-3);
        for (double& e : expected) e *= n / total;
        const test::ChiSquare r = test::chiSquare(observed, expected);
        EXPECT_LT(r.statistic, test::chiSquareCritical(r.dof));
    }
    // A ray through the lamp itself: the angle spans π, and every sample stays on the segment.
    const EquiangularSegment through(Vec3(0.f), Vec3(0, 1, 0), 0.f, 1.f, Vec3(0.f, 0.5f, 0.f));
    for (int i = 0; i < 1000; ++i) {
        const float t = through.sample(rng.get1D());
        ASSERT_TRUE(t >= 0.f && t <= 1.f) << t;
        ASSERT_TRUE(std::isfinite(through.pdf(t)));
    }
}

TEST(Equiangular, ConeIntervalMatchesAScanOfTheCone) {
    const Vec3 apex(0.f, 1.f, 0.f), axis(0.f, -1.f, 0.f);
    Sampler rng(3, 0, 0);
    for (float cosCone : {std::cos(radians(10.f)), std::cos(radians(40.f)), 0.1f}) {
        for (int trial = 0; trial < 200; ++trial) {
            const Vec3 o(4.f * rng.get1D() - 2.f, 2.f * rng.get1D() - 1.f, 4.f * rng.get1D() - 2.f);
            const Vec3 d =
                normalize(Vec3(rng.get1D() - 0.5f, rng.get1D() - 0.5f, rng.get1D() - 0.5f));
            const float a = 0.f, b = 5.f;
            // The scan: every 1/2000 of the segment inside the forward cone.
            float lo = kInfinity, hi = -kInfinity;
            for (int i = 0; i <= 2000; ++i) {
                const float t = a + (b - a) * i / 2000.f;
                const Vec3 v = o + d * t - apex;
                if (dot(v, axis) >= cosCone * length(v)) {
                    lo = std::min(lo, t);
                    hi = std::max(hi, t);
                }
            }
            float t0 = a, t1 = b;
            const bool hit = coneInterval(o, d, Cone{apex, axis, cosCone}, &t0, &t1);
            if (lo > hi) {
                // A miss, or a graze thinner than the scan's step.
                if (hit) {
                    EXPECT_LT(t1 - t0, 2 * (b - a) / 2000.f);
                }
                continue;
            }
            ASSERT_TRUE(hit);
            EXPECT_NEAR(t0, lo, 2 * (b - a) / 2000.f);
            EXPECT_NEAR(t1, hi, 2 * (b - a) / 2000.f);
        }
    }
    // A half-angle beyond 90° is the whole segment.
    float t0 = 0.f, t1 = 3.f;
    ASSERT_TRUE(coneInterval(Vec3(0.f), Vec3(1, 0, 0), Cone{apex, axis, -0.5f}, &t0, &t1));
    EXPECT_EQ(t0, 0.f);
    EXPECT_EQ(t1, 3.f);
}

namespace {

constexpr double kH = 1.0 / 32;
constexpr float kSigmaA = 0.2f, kSigmaS = 1.f, kPower = 50.f;

using Estimate = test::RayEstimate;

// Single scattering along `ray` by volpath cut after its first scattering event: next-event
// estimation at delta tracking's point, plus (equiangular) the point drawn towards the lamp.
Estimate singleScattering(RenderScene& scene, const Ray& ray, bool equiangular, int samples) {
    scene.equiangular = equiangular;
    return test::estimateAlongRay(*makeVolPathIntegrator(1), scene, ray, samples);
}

// ∫ T(0, t) σs p(θ) I f(x) T(t, lamp) / r² dt over the ray, in the angle the ray subtends at
// the lamp (t = Δ + D tan θ: smooth where the 1/r² peak is not), on the grid's own trilinear
// field (the box's faces fade over half a voxel).
double quadrature(const Medium& medium, const Ray& ray, const Vec3& lamp, double intensity,
                  const std::function<double(const Vec3&)>& falloff) {
    const FloatGrid& grid = medium.binding().grids()[0];
    auto acc = grid.accessor();
    const double sigmaT = kSigmaA + kSigmaS;
    const double delta = dot(lamp - ray.o, ray.d);
    const double D = length(ray.o + ray.d * float(delta) - lamp);
    // The ray from x = −0.2 to 1.2 crosses the box.
    return test::quadratureAlongRay(grid, ray, 0.0, 1.4, delta, D, sigmaT, [&](const Vec3& x) {
        const double density = grid.sample(acc, x);
        if (density <= 0) return 0.0;
        const double r = length(lamp - x);
        const double p = 1.0 / (4 * kPi);  // isotropic
        return kSigmaS * density * p * intensity * falloff(x) *
               std::exp(-test::opticalDepth(grid, x, lamp, sigmaT)) / (r * r);
    });
}

// A homogeneous haze over the box and a margin, bluer than red: σs falls linearly from `blue`
// at 360 nm to `red` at 830 nm (closed-form transmittance, a coloured medium).
void addHaze(RenderScene& scene, float sigmaA, float blue, float red) {
    ShaderDesc haze = test::greyShader(0.f, 0.f);
    haze.components[0].grid.clear();
    haze.components[0].sigmaA = Spectrum(sigmaA);
    haze.components[0].sigmaS = Spectrum::fromTable({360.f, 830.f}, {blue, red});
    Bounds3 box;
    box.lo = Vec3(-0.1f);
    box.hi = Vec3(1.1f);
    scene.media.push_back(std::make_unique<Medium>(haze, box, Transform(), 1.f));
}

RenderScene fogBox() {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, kSigmaA, kSigmaS));
    return scene;
}

}  // namespace

TEST(LampSampling, PointLightInFogMatchesQuadratureWithoutFireflies) {
    // The lamp in the middle of a 1 m box of fog; the camera ray passes 1 cm from it.
    const Vec3 lamp(0.5f, 0.5f, 0.5f);
    const Ray ray{Vec3(-0.2f, 0.51f, 0.5f), Vec3(1, 0, 0), kInfinity};
    RenderScene scene = fogBox();
    scene.lights.push_back(makePointLight(lamp, kPower, Spectrum(1.f)));
    const double I = kPower / (4 * kPi) / double(kLambdaMax - kLambdaMin);
    const double expected =
        quadrature(*scene.media[0], ray, lamp, I, [](const Vec3&) { return 1.0; });
    const Estimate eq = singleScattering(scene, ray, true, 40000);
    const Estimate dist = singleScattering(scene, ray, false, 40000);
    test::expectBothNear("point light in fog", expected, eq, dist);
    // Bounded near the lamp: the equiangular points carry the 1/r² peak.
    EXPECT_LT(eq.largest, 60 * eq.mean);
    EXPECT_LT(eq.se * 4, dist.se) << "equiangular's standard error is not 4× below distance's";
}

TEST(LampSampling, SpotBeamSeenFromTheSideMatchesQuadrature) {
    // A narrow spot at the top of the box shining down; the camera ray crosses its beam 0.6 m
    // below the lamp, from the side: only the cone's part of the ray is lit.
    const Vec3 lamp(0.5f, 0.95f, 0.5f), down(0.f, -1.f, 0.f);
    const float inner = 8.f, outer = 12.f;
    const Ray ray{Vec3(-0.2f, 0.35f, 0.5f), Vec3(1, 0, 0), kInfinity};
    RenderScene scene = fogBox();
    scene.lights.push_back(makeSpotLight(lamp, down, kPower, inner, outer, Spectrum(1.f)));
    const double ci = std::cos(radians(inner)), co = std::cos(radians(outer));
    const double I = kPower / (2 * kPi * (1 - 0.5 * (ci + co))) / double(kLambdaMax - kLambdaMin);
    const auto falloff = [&](const Vec3& x) {
        const double c = dot(normalize(x - lamp), down);
        if (c >= ci) return 1.0;
        if (c <= co) return 0.0;
        const double s = (c - co) / (ci - co);
        return s * s * (3 - 2 * s);
    };
    const double expected = quadrature(*scene.media[0], ray, lamp, I, falloff);
    const Estimate eq = singleScattering(scene, ray, true, 40000);
    const Estimate dist = singleScattering(scene, ray, false, 40000);
    test::expectBothNear("spot beam from the side", expected, eq, dist);
    // The beam is a small part of the ray: points drawn inside it are the win.
    EXPECT_LT(eq.se * 2, dist.se);
}

TEST(LampSampling, SmokeAndHazeKeepTheMeanPerWavelength) {
    // The equiangular points' transmittance read off the path's own flight (lamp_sampling.h),
    // through a heterogeneous grid (density rising along x, ratio-tracked) and a coloured
    // homogeneous haze over it (closed form), along paths of many bounces: every segment's
    // flight either passes its point or stops short of it and is finished by tracking. Its mean
    // must be distance sampling's (which reads no such estimate), at each of the four
    // wavelengths.
    RenderScene scene;
    scene.media.push_back(test::gridMedium([](int i, int, int) { return 0.2f + 0.05f * i; }, 0, 31,
                                           kH, 0.4f, 1.2f, 0.3f));
    addHaze(scene, 0.1f, 3.f, 1.f);
    scene.lights.push_back(makePointLight(Vec3(0.5f, 0.5f, 0.5f), kPower, Spectrum(1.f)));
    const Ray ray{Vec3(-0.2f, 0.6f, 0.5f), Vec3(1, 0, 0), kInfinity};
    const auto volpath = makeVolPathIntegrator(16);
    scene.equiangular = true;
    const auto eq = test::estimateAlongRayPerWavelength(*volpath, scene, ray, 40000);
    scene.equiangular = false;
    const auto dist = test::estimateAlongRayPerWavelength(*volpath, scene, ray, 80000);
    for (int k = 0; k < kSpectrumSamples; ++k) {
        std::printf("λ%d: equiangular %.5g ± %.2g, distance %.5g ± %.2g\n", k, eq[k].mean, eq[k].se,
                    dist[k].mean, dist[k].se);
        EXPECT_NEAR(eq[k].mean, dist[k].mean, 4 * std::hypot(eq[k].se, dist[k].se)) << "λ" << k;
    }
}

// The camera ray's points for the lights at infinity (lamp_sampling.h): through a thin medium
// under a constant white dome, where delta tracking scatters on one sample in ten, they keep
// the mean at every wavelength (a coloured haze over the smoke, paths of many bounces) and
// lower the noise of the pixel.
TEST(LampSampling, TheDomesPointsOnTheCameraRayKeepTheMeanAndLowerTheNoise) {
    RenderScene scene;
    scene.media.push_back(test::gridMedium([](int i, int, int) { return 0.02f + 0.004f * i; }, 0,
                                           31, kH, 0.02f, 0.1f, 0.6f));
    addHaze(scene, 0.01f, 0.06f, 0.02f);
    DomeSettings hidden;
    hidden.cameraVisible = false;
    scene.lights.push_back(makeDomeLight(Spectrum(1.f), hidden));
    const Ray ray{Vec3(-0.2f, 0.6f, 0.5f), Vec3(1, 0, 0), kInfinity};
    const auto volpath = makeVolPathIntegrator(16);
    scene.equiangular = true;
    ASSERT_TRUE(samplesSky(scene));
    const auto sky = test::estimateAlongRayPerWavelength(*volpath, scene, ray, 40000);
    scene.equiangular = false;
    const auto dist = test::estimateAlongRayPerWavelength(*volpath, scene, ray, 40000);
    for (int k = 0; k < kSpectrumSamples; ++k) {
        std::printf("λ%d: the dome's points %.5g ± %.2g, delta tracking's %.5g ± %.2g\n", k,
                    sky[k].mean, sky[k].se, dist[k].mean, dist[k].se);
        EXPECT_NEAR(sky[k].mean, dist[k].mean, 4 * std::hypot(sky[k].se, dist[k].se)) << "λ" << k;
        EXPECT_LT(sky[k].se * 2, dist[k].se) << "λ" << k;
    }
}

namespace {

// The grid's rows j = 17 and 18 a slab of density 3, the rest a wisp of density `wisp`; σs = 4
// per unit density, σa and the phase function's g as given. A ray along x at y = 16 h crosses
// the wisp in majorant cells that hold the slab.
std::unique_ptr<Medium> wispBesideSlab(float wisp, float sigmaA, float g) {
    return test::gridMedium([wisp](int, int j, int) { return j == 17 || j == 18 ? 3.f : wisp; },
                            0, 31, kH, sigmaA, 4.f, g);
}

}  // namespace

// A thin wisp beside a dense slab: the majorant cells the camera ray crosses hold the slab's
// density, 1000 times the wisp's, so the majorant's optical depth along the ray (about 12)
// says nothing of its real one (0.012). The dome's points lie uniformly in the ray's marched
// depth and are weighed against delta tracking's scattering points by their densities: left to
// delta tracking, the ray is a coin of probability 1 % and a value a hundred times the mean
// (single scattering: paths cut after one event). With paths of every length, the scene forks
// (skyPointsFork): the lit point starts a second path and delta tracking's goes on with the
// probability of its weight; the mean stays, and the light scattered again off the slab comes
// through the lit points too. There the second path's roulette measures it against its own
// weight (~0.01; against 1, nine paths in ten ended at its first vertex). With the points by
// the majorant's depth and that roulette, the noise at depth 16 was a third of delta
// tracking's alone; a thirteenth now.
TEST(LampSampling, TheDomesPointsStayQuietWhereTheMajorantIsLoose) {
    RenderScene scene;
    scene.media.push_back(wispBesideSlab(0.003f, 0.02f, 0.6f));
    DomeSettings hidden;
    hidden.cameraVisible = false;
    scene.lights.push_back(makeDomeLight(Spectrum(1.f), hidden));
    ASSERT_TRUE(skyPointsFork(scene));
    const Ray ray{Vec3(-0.2f, float(16 * kH), 0.5f), Vec3(1, 0, 0), kInfinity};
    for (int depth : {1, 16}) {
        const auto volpath = makeVolPathIntegrator(depth);
        scene.equiangular = true;
        const Estimate sky = test::estimateAlongRay(*volpath, scene, ray, 40000);
        scene.equiangular = false;
        const Estimate dist = test::estimateAlongRay(*volpath, scene, ray, 40000);
        std::printf("depth %d: the dome's points %.5g ± %.2g, delta tracking's %.5g ± %.2g\n",
                    depth, sky.mean, sky.se, dist.mean, dist.se);
        EXPECT_NEAR(sky.mean, dist.mean, 4 * std::hypot(sky.se, dist.se)) << depth;
        EXPECT_LT(sky.se * 8, dist.se) << depth;
    }
}

// A wisp (optical depth 0.2 along the ray) beside a dense slab, in a cloud's medium (albedo
// 0.99, g = 0.85) under a sky map with a small sun: its paths are guided (render/light_lobes.h:
// guidesPaths), and the camera ray's points for the sky and their second path are theirs too,
// the second path guided as the first (a lobe walk from the lit point, and its share in the
// next vertex's weights). The mean stays that of delta tracking's points alone, per wavelength
// (without that share, the walk's light counted twice: +13 %), and the noise falls (2.3× here).
// Until 2026-11-30 guided paths drew no such points, and both estimates here were the same.
TEST(LampSampling, TheDomesPointsForkGuidedPathsUnderASun) {
    RenderScene scene;
    scene.media.push_back(wispBesideSlab(0.05f, 0.04f, 0.85f));
    LatLongImage sky;
    sky.width = 256;
    sky.height = 128;
    sky.rgb.assign(size_t(sky.width) * sky.height * 3, 0.2f);
    for (int c = 0; c < 3; ++c) sky.rgb[3 * (size_t(40) * sky.width + 100) + c] = 4e4f;
    DomeSettings hidden;
    hidden.cameraVisible = false;
    scene.lights.push_back(makeDomeLight(sky, 1.f, Mat3(), hidden));
    ASSERT_TRUE(guidesPaths(scene));
    ASSERT_TRUE(skyPointsFork(scene));
    const Ray ray{Vec3(-0.2f, float(16 * kH), 0.5f), Vec3(1, 0, 0), kInfinity};
    const auto volpath = makeVolPathIntegrator(16);
    scene.equiangular = true;
    const auto points = test::estimateAlongRayPerWavelength(*volpath, scene, ray, 160000);
    scene.equiangular = false;
    const auto dist = test::estimateAlongRayPerWavelength(*volpath, scene, ray, 160000);
    for (int k = 0; k < kSpectrumSamples; ++k) {
        std::printf("λ%d: the sky's points %.5g ± %.2g, delta tracking's %.5g ± %.2g\n", k,
                    points[k].mean, points[k].se, dist[k].mean, dist[k].se);
        EXPECT_NEAR(points[k].mean, dist[k].mean, 4 * std::hypot(points[k].se, dist[k].se))
            << "λ" << k;
        EXPECT_LT(points[k].se * 1.5, dist[k].se) << "λ" << k;
    }
}
