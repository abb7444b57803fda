// Sphere lights (light/lamp.cpp): directions drawn uniformly in the cone the sphere subtends
// (χ²), the irradiance it gives a surface facing it (Φ / 4πd², the point light's, and Lambert's
// cosine on a tilted surface), the point light as r → 0, photons leaving its surface with the
// flux of a constant radiance (χ² of the projected disc), its total power for point and spot
// profiles, and the render's estimate in fog unbiased with and without the distances drawn
// towards its centre (render/lamp_sampling.h) and, on a ray through the sphere, equal to
// quadrature; the same bits on one thread and two.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "light/lamp.h"
#include "render/renderer.h"
#include "test_support.h"

using namespace mirage;

namespace {

constexpr float kPower = 40.f;
constexpr double kBand = double(kLambdaMax - kLambdaMin);  // a white light's 1/nm

std::unique_ptr<Light> sphere(const Vec3& c, float r, float power = kPower) {
    LampDesc d;
    d.position = c;
    d.radius = r;
    d.powerW = power;
    return makeLamp(d, Spectrum(1.f));
}

test::ChiSquare uniformChiSquare(const std::vector<double>& values, int bins) {
    std::vector<double> observed(bins, 0.0), expected(bins, double(values.size()) / bins);
    for (double v : values) observed[std::min(bins - 1, std::max(0, int(v * bins)))] += 1;
    return test::chiSquare(observed, expected);
}

const SampledWavelengths kW = SampledWavelengths::sampleVisible(0.3f);

}  // namespace

TEST(SphereLight, DirectionsAreUniformInTheSubtendedCone) {
    const Vec3 c(0.3f, 1.f, -0.2f), p(0.f, -1.f, 0.5f);
    const float r = 0.8f;
    auto light = sphere(c, r);
    const float d = length(c - p), cosMax = std::sqrt(1.f - r * r / (d * d));
    const Vec3 axis = normalize(c - p);
    const Frame frame(axis);
    // Li = L / pdf = I 2π(1 − cos θmax) / (π r²), the same for every direction.
    const double expectedLi = kPower / (4 * kPi) / kBand * 2 * (1 - cosMax) / (r * r);
    Sampler s(3, 0, 0);
    std::vector<double> u, phi;
    for (int i = 0; i < 200000; ++i) {
        LightSample ls;
        const float u1 = s.get1D(), u2 = s.get1D();
        ASSERT_TRUE(light->sampleLi(p, u1, u2, kW, &ls));
        const double cosA = dot(ls.wi, axis);
        ASSERT_GE(cosA, cosMax - 1e-5);
        // The sample lies on the sphere's near side.
        const Vec3 q = p + ls.wi * ls.distance;
        ASSERT_NEAR(length(q - c), r, 1e-4f);
        ASSERT_LT(dot(q - c, ls.wi), 1e-4f);
        ASSERT_NEAR(ls.Li[0], expectedLi, 1e-4 * expectedLi);
        u.push_back(std::min(0.999999, (1 - cosA) / (1 - cosMax)));
        const Vec3 l = frame.toLocal(ls.wi);
        phi.push_back((std::atan2(l.y, l.x) + kPi) / (2 * kPi));
    }
    for (const auto* v : {&u, &phi}) {
        const test::ChiSquare chi = uniformChiSquare(*v, 40);
        EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof));
    }
}

TEST(SphereLight, IrradianceIsThePointLightsOutsideTheSphere) {
    // E = ∫ Li cos θ dω over the cone: Φ / (4π d²) facing the centre, × cos β on a surface
    // tilted by β (the whole sphere above its horizon), as for the point light at the centre.
    const Vec3 c(0.f), p(0.f, 0.f, 3.f);
    const float r = 1.f;
    auto light = sphere(c, r);
    const double facing = kPower / (4 * kPi * 9.0) / kBand;
    for (float tiltDeg : {0.f, 40.f}) {
        const float b = radians(tiltDeg);
        const Vec3 n(std::sin(b), 0.f, -std::cos(b));  // the surface at p faces the sphere
        test::SampleMean e;
        Sampler s(5, 0, 0);
        for (int i = 0; i < 100000; ++i) {
            LightSample ls;
            const float u1 = s.get1D(), u2 = s.get1D();
            ASSERT_TRUE(light->sampleLi(p, u1, u2, kW, &ls));
            e.add(ls.Li[0] * std::max(0.f, dot(ls.wi, n)));
        }
        SCOPED_TRACE("tilt " + std::to_string(tiltDeg));
        EXPECT_NEAR(e.mean(), facing * std::cos(b), 4 * e.standardError() + 1e-6 * facing);
    }
    // Inside the sphere the light sends nothing (its surface emits outwards).
    LightSample ls;
    EXPECT_FALSE(light->sampleLi(Vec3(0.2f, 0.f, 0.5f), 0.5f, 0.5f, kW, &ls));
}

TEST(SphereLight, ShrinksToThePointLight) {
    const Vec3 c(1.f, 2.f, 3.f), p(0.f, 0.5f, 1.f);
    auto point = makePointLight(c, kPower, Spectrum(1.f));
    LightSample pl;
    ASSERT_TRUE(point->sampleLi(p, 0.5f, 0.5f, kW, &pl));
    for (float r : {1e-1f, 1e-2f, 1e-3f}) {
        auto light = sphere(c, r);
        Sampler s(11, 0, 0);
        double worstLi = 0, worstDir = 0;
        for (int i = 0; i < 1000; ++i) {
            LightSample ls;
            const float u1 = s.get1D(), u2 = s.get1D();
            ASSERT_TRUE(light->sampleLi(p, u1, u2, kW, &ls));
            worstLi = std::max(worstLi, std::abs(ls.Li[0] / pl.Li[0] - 1.0));
            worstDir = std::max(worstDir, double(length(ls.wi - pl.wi)));
        }
        // The radiance's share of the cone is exact; the direction strays by θmax ≈ r/d.
        SCOPED_TRACE("r = " + std::to_string(r));
        EXPECT_LT(worstLi, 2 * r * r + 1e-5);
        EXPECT_LT(worstDir, 1.1 * r / length(c - p) + 1e-6);
    }
}

TEST(SphereLight, PhotonsLeaveItsSurfaceWithAConstantRadiance) {
    // Isotropic directions; for each, the origin's offset across the direction is uniform on
    // the disc of radius r (ρ²/r² uniform), lifted to the side facing the direction.
    const Vec3 c(0.f, 1.f, 0.f);
    const float r = 0.5f;
    auto light = sphere(c, r);
    Bounds3 around;  // the lamp inside the scene: no aiming
    around.expand(Vec3(-3.f));
    around.expand(Vec3(3.f));
    EXPECT_FLOAT_EQ(light->emittedPower(around), kPower);
    Sampler s(2, 0, 0);
    std::vector<double> rho2, z;
    for (int i = 0; i < 200000; ++i) {
        PhotonEmission e;
        ASSERT_TRUE(light->emitPhoton(around, s, &e));
        ASSERT_EQ(e.weight, 1.f);
        const Vec3 o = e.origin - c;
        ASSERT_NEAR(length(o), r, 1e-5f);
        ASSERT_GE(dot(o, e.direction), -1e-6f);
        const Vec3 across = o - e.direction * dot(o, e.direction);
        rho2.push_back(std::min(0.999999, double(dot(across, across)) / (r * r)));
        z.push_back(0.5 * (e.direction.z + 1.0));
    }
    for (const auto* v : {&rho2, &z}) {
        const test::ChiSquare chi = uniformChiSquare(*v, 40);
        EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof));
    }
}

TEST(SphereLight, AimedPhotonsKeepThePowerThatReachesTheScene) {
    // A sphere 10 m from a 1 m box: photons aimed in the cone widened by the lamp's radius
    // carry the same power onto the box as the unaimed lamp's.
    Bounds3 box;
    box.expand(Vec3(9.5f, -0.5f, -0.5f));
    box.expand(Vec3(10.5f, 0.5f, 0.5f));
    Bounds3 everywhere;
    everywhere.expand(Vec3(-1e-3f));
    everywhere.expand(Vec3(1e-3f));
    auto light = sphere(Vec3(0.f), 2.f);
    auto onBox = [&](const Bounds3& aim, uint64_t seed, int n) {
        test::SampleMean m;
        Sampler s(seed, 0, 0);
        const float power = light->emittedPower(aim);
        for (int i = 0; i < n; ++i) {
            PhotonEmission e;
            float t0, t1;
            const bool ok = light->emitPhoton(aim, s, &e);
            m.add(ok && box.intersect(e.origin, e.direction, 0.f, kInfinity, &t0, &t1)
                      ? power * e.weight
                      : 0.0);
        }
        return m;
    };
    const test::SampleMean aimed = onBox(box, 3, 200000), all = onBox(everywhere, 4, 4000000);
    ASSERT_GT(all.mean(), 0.0);
    EXPECT_NEAR(aimed.mean(), all.mean(),
                4 * std::hypot(aimed.standardError(), all.standardError()));
}

TEST(SphereLight, SpotSphereRadiatesItsPower) {
    // ∫ I dω = Φ: the photons' mean weight is 1 over the spot's own cone, and the render
    // pass's radiance agrees with the point spot's far from the lamp.
    LampDesc d;
    d.position = Vec3(0.f);
    d.radius = 0.05f;
    d.powerW = kPower;
    d.profile.axis = Vec3(0.f, -1.f, 0.f);
    d.profile.spot = true;
    d.profile.innerDeg = 20.f;
    d.profile.outerDeg = 35.f;
    auto light = makeLamp(d, Spectrum(1.f));
    auto point = makeSpotLight(d.position, d.profile.axis, kPower, 20.f, 35.f, Spectrum(1.f));
    Bounds3 around;
    around.expand(Vec3(-3.f));
    around.expand(Vec3(3.f));
    test::SampleMean w;
    Sampler s(6, 0, 0);
    for (int i = 0; i < 200000; ++i) {
        PhotonEmission e;
        w.add(light->emitPhoton(around, s, &e) ? e.weight : 0.0);
    }
    EXPECT_NEAR(w.mean(), 1.0, 4 * w.standardError());
    const Vec3 far(3.f, -30.f, 0.f);  // 5.7° off the axis: inside the inner cone
    LightSample ls, pl;
    ASSERT_TRUE(light->sampleLi(far, 0.3f, 0.7f, kW, &ls));
    ASSERT_TRUE(point->sampleLi(far, 0.5f, 0.5f, kW, &pl));
    EXPECT_NEAR(ls.Li[0], pl.Li[0], 1e-5 * pl.Li[0]);
    // The lamp-sampling cone holds the sphere: its apex sits r / sin θo behind the centre.
    const auto* lamp = dynamic_cast<const Lamp*>(light.get());
    ASSERT_TRUE(lamp);
    const Vec3 apex = lamp->coneApex();
    EXPECT_NEAR(length(apex - d.position), 0.05f / std::sin(radians(35.f)), 1e-6f);
    EXPECT_LT(dot(apex - d.position, d.profile.axis), 0.f);
}

namespace {

constexpr double kH = 1.0 / 32;

// A sphere lamp in the middle of a 1 m box of thin fog; single scattering along a ray that
// passes 5 cm outside its surface.
RenderScene sphereInFog(float r) {
    RenderScene scene;
    scene.media.push_back(
        test::gridMedium([](int, int, int) { return 1.f; }, 0, 31, kH, 0.2f, 1.f));
    scene.lights.push_back(sphere(Vec3(0.5f), r, 50.f));
    return scene;
}

}  // namespace

TEST(SphereLight, LampSamplingStaysUnbiased) {
    // With and without the distances drawn towards the centre, the estimates agree; and they
    // stay close to the point light's (the fog is thin, the sphere small against the ray's
    // distance: only the cone's spread differs).
    const Ray ray{Vec3(-0.2f, 0.5f, 0.65f), Vec3(1, 0, 0), kInfinity};
    RenderScene scene = sphereInFog(0.1f);
    auto integrator = makeVolPathIntegrator(1);
    scene.equiangular = true;
    const test::RayEstimate eq = test::estimateAlongRay(*integrator, scene, ray, 40000);
    scene.equiangular = false;
    const test::RayEstimate dist = test::estimateAlongRay(*integrator, scene, ray, 40000);
    std::printf("sphere in fog: equiangular %.5g ± %.2g, distance %.5g ± %.2g\n", eq.mean, eq.se,
                dist.mean, dist.se);
    EXPECT_NEAR(eq.mean, dist.mean, 4 * std::hypot(eq.se, dist.se));
    EXPECT_LT(eq.se, dist.se);
}

namespace {

// Single scattering from a sphere lamp at x, by quadrature: L ∫ T(x → surface) dω over the cone
// the sphere subtends (dω = 2π d cos α), the near surface at s(α) = d cos α − √(r² − d² sin² α)
// along a direction α off the axis; nothing inside the sphere, whose surface emits outwards. The
// fog is homogeneous along these short shadow paths (the box's faded faces lie ≥ 0.45 m away
// from the lamp, ≤ 1/64 m deep).
double sphereInScatter(const Vec3& x, const Vec3& c, double r, double radiance, double sigmaT) {
    const double d = length(c - x);
    if (d <= r) return 0.0;
    const double cosMax = std::sqrt(1.0 - r * r / (d * d));
    const int n = 64;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double mu = cosMax + (1.0 - cosMax) * (i + 0.5) / n;
        const double s = d * mu - std::sqrt(std::max(0.0, r * r - d * d * (1.0 - mu * mu)));
        sum += std::exp(-sigmaT * s);
    }
    return 2 * kPi * radiance * sum * (1.0 - cosMax) / n;
}

}  // namespace

TEST(SphereLight, SingleScatteringThroughItMatchesQuadratureWithoutFireflies) {
    // A camera ray through the sphere lamp, 2 cm from its centre (r = 5 cm): the points inside
    // receive nothing, those beside its surface the most. The sphere bounds the light's 1/d²
    // (the largest sample of delta tracking alone is ~30 × the mean); equiangular distances
    // towards the centre halve that and lower the noise ~1.5×.
    const Vec3 c(0.5f);
    const double r = 0.05, sigmaS = 1.0, sigmaT = 1.2;
    const Ray ray{Vec3(-0.2f, 0.52f, 0.5f), Vec3(1, 0, 0), kInfinity};
    RenderScene scene = sphereInFog(float(r));
    const FloatGrid& grid = scene.media[0]->binding().grids()[0];
    auto acc = grid.accessor();
    const double radiance = 50.0 / (4 * kPi) / kBand / (kPi * r * r);
    // ∫ T(0, t) σs ρ(x) p S(x) dt about the point nearest the centre, 2 cm from it at t = 0.7.
    const double expected =
        test::quadratureAlongRay(grid, ray, 0.0, 1.4, 0.7, 0.02, sigmaT, [&](const Vec3& x) {
            return sigmaS * grid.sample(acc, x) / (4 * kPi) *
                   sphereInScatter(x, c, r, radiance, sigmaT);
        });
    auto integrator = makeVolPathIntegrator(1);
    scene.equiangular = true;
    const test::RayEstimate eq = test::estimateAlongRay(*integrator, scene, ray, 40000);
    scene.equiangular = false;
    const test::RayEstimate dist = test::estimateAlongRay(*integrator, scene, ray, 40000);
    test::expectBothNear("through the sphere", expected, eq, dist);
    EXPECT_LT(eq.largest, 20 * eq.mean);
    EXPECT_LT(eq.largest, dist.largest);
    EXPECT_LT(eq.se, dist.se);
}

TEST(SphereLight, RendersTheSameBitsOnOneAndTwoThreads) {
    RenderScene scene = sphereInFog(0.2f);
    scene.camera.position = Vec3(0.5f, 0.5f, 3.f);
    scene.camera.lookAt = Vec3(0.5f);
    auto integrator = makeVolPathIntegrator();
    const RenderSettings settings = test::smallRenderSettings(4, 9, 16, 16);
    auto withThreads = [&](size_t threads) {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, threads);
        return render(scene, *integrator, settings, nullptr);
    };
    EXPECT_TRUE(test::sameFilm(withThreads(1), withThreads(2)));
}
