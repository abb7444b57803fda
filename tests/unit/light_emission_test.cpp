// Photon emission of every light type: directions and origins follow the emitted radiance (χ²
// and moment tests), the power a light reports matches the radiance it shows the render pass,
// a distant light covers the scene's bounding disc, wavelengths follow the light's colour.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "core/surface_epsilon.h"
#include "light/light.h"

using namespace mirage;

namespace {

Bounds3 box(const Vec3& lo, const Vec3& hi) {
    Bounds3 b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

// A histogram of values in [0, 1) against the uniform density.
test::ChiSquare uniformChiSquare(const std::vector<double>& values, int bins) {
    std::vector<double> observed(bins, 0.0), expected(bins, double(values.size()) / bins);
    for (double v : values) observed[std::min(bins - 1, std::max(0, int(v * bins)))] += 1;
    return test::chiSquare(observed, expected);
}

struct Moment {
    double mean, stderr_;
};
Moment moment(const std::vector<double>& v) {
    double s = 0, s2 = 0;
    for (double x : v) {
        s += x;
        s2 += x * x;
    }
    double m = s / v.size();
    return {m, std::sqrt(std::max(0.0, s2 / v.size() - m * m) / v.size())};
}

const Bounds3 kScene = box(Vec3(-1.f), Vec3(1.f));
constexpr int kN = 200000;

}  // namespace

TEST(LightEmission, PointLightIsIsotropic) {
    // Inside the scene's bounding sphere (radius √3): every direction may reach something.
    auto light = makePointLight(Vec3(0.5f, 0.f, 1.f), 40.f, Spectrum(1.f));
    EXPECT_FLOAT_EQ(light->emittedPower(kScene), 40.f);
    Sampler s(1, 0, 0);
    std::vector<double> z, phi;
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e;
        ASSERT_TRUE(light->emitPhoton(kScene, s, &e));
        ASSERT_EQ(e.origin, Vec3(0.5f, 0.f, 1.f));
        ASSERT_NEAR(length(e.direction), 1.f, 1e-5f);
        ASSERT_EQ(e.weight, 1.f);
        // Uniform on the sphere: z and the azimuth are both uniform (Archimedes).
        z.push_back(0.5 * (e.direction.z + 1.0));
        phi.push_back((std::atan2(e.direction.y, e.direction.x) + kPi) / (2 * kPi));
    }
    for (const auto* v : {&z, &phi}) {
        test::ChiSquare c = uniformChiSquare(*v, 40);
        EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
    }
}

// The fraction of uniform directions from p that hit the box b (slab test), by Monte Carlo
// over the whole sphere: an estimate that knows nothing of the lights' aiming.
Moment boxSolidAngleFraction(const Vec3& p, const Bounds3& b, int n, uint64_t seed) {
    Sampler s(seed, 0, 0);
    std::vector<double> hit;
    for (int i = 0; i < n; ++i) {
        float u1 = s.get1D(), u2 = s.get1D();
        float z = 1.f - 2.f * u1, r = std::sqrt(std::max(0.f, 1.f - z * z));
        Vec3 d(r * std::cos(2 * kPi * u2), r * std::sin(2 * kPi * u2), z);
        float t0, t1;
        hit.push_back(b.intersect(p, d, 0.f, kInfinity, &t0, &t1) ? 1.0 : 0.0);
    }
    return moment(hit);
}

TEST(LightEmission, PointLightOutsideTheSceneAimsAtIt) {
    // A small cache 30 m away: the photons leave inside the cone its bounding sphere subtends,
    // each of weight 1, and the power that meets the box is I × Ω(box) as over the full sphere.
    const Bounds3 cache = box(Vec3(29.f, -0.5f, -1.f), Vec3(30.f, 0.5f, 0.5f));
    const Vec3 p(0.f, 1.f, 0.f);
    const float power = 40.f;
    auto light = makePointLight(p, power, Spectrum(1.f));
    const Vec3 axis = normalize(cache.center() - p);
    const float d = length(cache.center() - p), r = 0.5f * length(cache.diagonal());
    const float cosMax = std::sqrt(d * d - r * r) / d;
    const float emitted = light->emittedPower(cache);
    EXPECT_NEAR(emitted, power * 0.5f * (1.f - cosMax), 1e-6f * power);
    EXPECT_LT(emitted, 1e-3f * power);  // the full sphere would waste > 99.9 % of them
    Sampler s(7, 0, 0);
    std::vector<double> u, hits;
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e;
        ASSERT_TRUE(light->emitPhoton(cache, s, &e));
        ASSERT_EQ(e.weight, 1.f);
        const double c = dot(e.direction, axis);
        ASSERT_GE(c, cosMax - 1e-6);
        u.push_back((c - cosMax) / (1.0 - cosMax));  // uniform in the cone: cos θ uniform
        float t0, t1;
        hits.push_back(cache.intersect(p, e.direction, 0.f, kInfinity, &t0, &t1) ? emitted : 0.0);
    }
    test::ChiSquare c = uniformChiSquare(u, 40);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
    const Moment aimed = moment(hits);
    const Moment frac = boxSolidAngleFraction(p, cache, 40000000, 8);
    const double expected = power * frac.mean, expectedSe = power * frac.stderr_;
    EXPECT_NEAR(aimed.mean, expected, 4 * std::hypot(aimed.stderr_, expectedSe));
}

TEST(LightEmission, SpotLightWiderThanTheSceneAimsAtIt) {
    // A 60° spot 20 m from a 1 m cache: the scene's cone is narrower than the spot's, so the
    // photons go there, carrying the falloff and the cones' solid-angle ratio; the power that
    // meets the box equals that of the unaimed spot (uniform over its own cone).
    const Bounds3 cache = box(Vec3(19.5f, -0.5f, -0.5f), Vec3(20.5f, 0.5f, 0.5f));
    const Vec3 p(0.f), axis = normalize(Vec3(1.f, 0.1f, 0.f));
    auto light = makeSpotLight(p, axis, 12.f, 20.f, 60.f, Spectrum(1.f));
    const Bounds3 everywhere = box(Vec3(-1e-3f), Vec3(1e-3f));  // light inside: no aiming
    auto powerOnBox = [&](const Bounds3& aimAt, uint64_t seed, int n) {
        Sampler s(seed, 0, 0);
        std::vector<double> hits;
        const float emitted = light->emittedPower(aimAt);
        for (int i = 0; i < n; ++i) {
            PhotonEmission e;
            float t0, t1;
            const bool ok = light->emitPhoton(aimAt, s, &e);
            hits.push_back(ok && cache.intersect(p, e.direction, 0.f, kInfinity, &t0, &t1)
                               ? emitted * e.weight
                               : 0.0);
        }
        return moment(hits);
    };
    const Moment aimed = powerOnBox(cache, 9, kN), unaimed = powerOnBox(everywhere, 10, 20 * kN);
    ASSERT_GT(unaimed.mean, 0.0);
    EXPECT_NEAR(aimed.mean, unaimed.mean, 4 * std::hypot(aimed.stderr_, unaimed.stderr_));
    // Aimed, every photon meets the box's sphere; the aimed estimate is far less noisy.
    EXPECT_LT(aimed.stderr_, 0.2 * unaimed.stderr_ * std::sqrt(20.0));
}

TEST(LightEmission, SpotPhotonsStayInTheConeAndCarryTheFalloff) {
    const float inner = 20.f, outer = 35.f, power = 12.f;
    const Vec3 pos(0.f, 0.f, 3.f), axis = normalize(Vec3(0.2f, 0.1f, -1.f));
    auto light = makeSpotLight(pos, axis, power, inner, outer, Spectrum(1.f));
    EXPECT_FLOAT_EQ(light->emittedPower(kScene), power);
    const double cosO = std::cos(outer * M_PI / 180), cosI = std::cos(inner * M_PI / 180);
    Sampler s(2, 0, 0);
    std::vector<double> u, w, wInner;
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e;
        ASSERT_TRUE(light->emitPhoton(kScene, s, &e));
        double c = dot(e.direction, axis);
        ASSERT_GE(c, cosO - 1e-6);
        // Uniform in solid angle over the cone: cosθ uniform in [cosOuter, 1].
        u.push_back((c - cosO) / (1.0 - cosO));
        w.push_back(e.weight);
        wInner.push_back(c >= cosI ? e.weight : 0.0);
    }
    test::ChiSquare c = uniformChiSquare(u, 40);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
    // Mean weight 1 (photon power Φ/N × w is unbiased), and the inner cone, where f = 1, gets
    // the share (1 − cosI) / (1 − (cosI + cosO)/2) of the power (smoothstep ramp: half width).
    Moment mw = moment(w), mi = moment(wInner);
    EXPECT_NEAR(mw.mean, 1.0, 4 * mw.stderr_);
    double innerShare = (1 - cosI) / (1 - 0.5 * (cosI + cosO));
    EXPECT_NEAR(mi.mean, innerShare, 4 * mi.stderr_);
}

TEST(LightEmission, SpotPowerMatchesTheIntensityItShowsTheRenderPass) {
    // Φ = ∫ I(ω) dω, with I(ω) = Li·d² from sampleLi at distance d: the power the photon pass
    // emits is the power the render pass sees. Uniform directions, I integrated by MC.
    const float power = 7.f;
    const Vec3 pos(1.f, 2.f, 3.f), axis(0.f, 0.f, -1.f);
    auto light = makeSpotLight(pos, axis, power, 15.f, 40.f, Spectrum(1.f));
    SampledWavelengths w;
    w.lambda.fill(550.f);
    w.pdf.fill(1.f);
    Sampler s(3, 0, 0);
    std::vector<double> est;
    const float d = 2.f;
    for (int i = 0; i < kN; ++i) {
        float u1 = s.get1D(), u2 = s.get1D();
        float z = 1.f - 2.f * u1, r = std::sqrt(std::max(0.f, 1.f - z * z));
        Vec3 dir(r * std::cos(2 * kPi * u2), r * std::sin(2 * kPi * u2), z);
        LightSample ls;
        double I = light->sampleLi(pos + dir * d, 0.5f, 0.5f, w, &ls) ? ls.Li[0] * d * d : 0.0;
        // Li is per nm: the normalised white SPD is 1/470 nm⁻¹.
        est.push_back(4 * M_PI * I * (kLambdaMax - kLambdaMin));
    }
    Moment m = moment(est);
    EXPECT_NEAR(m.mean, power, 4 * m.stderr_ + 1e-3 * power);
}

TEST(LightEmission, QuadLightIsCosineWeightedFromAUniformPoint) {
    const Vec3 corner(-1.f, 0.5f, 2.f), eu(2.f, 0.f, 0.f), ev(0.f, 1.f, 0.5f);
    auto light = makeQuadLight(corner, eu, ev, 30.f, Spectrum(1.f));
    EXPECT_FLOAT_EQ(light->emittedPower(kScene), 30.f);
    const Vec3 n = normalize(cross(eu, ev));
    Sampler s(4, 0, 0);
    std::vector<double> cos2, phi, a, b;
    const Frame f(n);
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e;
        ASSERT_TRUE(light->emitPhoton(kScene, s, &e));
        ASSERT_EQ(e.weight, 1.f);
        Vec3 local = f.toLocal(e.direction);
        ASSERT_GE(local.z, 0.f);
        // Cosine-weighted: p(θ) dθ ∝ cosθ sinθ, so cos²θ is uniform in [0, 1].
        cos2.push_back(double(local.z) * local.z);
        phi.push_back((std::atan2(local.y, local.x) + kPi) / (2 * kPi));
        // The origin's coordinates along the edges are uniform in [0, 1].
        Vec3 q = e.origin - corner;
        a.push_back(dot(q, eu) / dot(eu, eu));
        b.push_back(dot(q, ev) / dot(ev, ev));
        // Off the quad on its emitting side by the surface epsilon, so that a surface lying
        // in the quad's plane (a ceiling) is not hit at t ≈ 0.
        const float off = surfaceEpsilon(e.origin);
        ASSERT_GT(dot(q, n), 0.5f * off);
        ASSERT_LT(dot(q, n), 1.5f * off);
    }
    for (const auto* v : {&cos2, &phi, &a, &b}) {
        test::ChiSquare c = uniformChiSquare(*v, 40);
        EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
    }
}

TEST(LightEmission, DistantLightCoversTheSceneDisc) {
    // A small cache far from the origin: the disc follows the scene, not the world.
    const Bounds3 cache = box(Vec3(100.f, 50.f, 20.f), Vec3(101.f, 52.f, 21.5f));
    const Vec3 c = cache.center(), dir = normalize(Vec3(0.3f, -0.2f, -1.f));
    const float E = 800.f, r = 0.5f * length(cache.diagonal());
    auto light = makeDistantLight(dir, E, Spectrum(1.f));
    const float power = light->emittedPower(cache);
    EXPECT_NEAR(power, E * kPi * r * r, 1e-4f * power);
    EXPECT_EQ(light->emittedPower(Bounds3()), 0.f);

    // A square target of side 0.5 m through the centre, facing the light: the photons that
    // cross it carry E × 0.25 m² (the disc is lit uniformly).
    const Frame f(dir);
    const float side = 0.5f;
    Sampler s(5, 0, 0);
    std::vector<double> rho2, hits;
    for (int i = 0; i < kN; ++i) {
        PhotonEmission e;
        ASSERT_TRUE(light->emitPhoton(cache, s, &e));
        ASSERT_NEAR(dot(e.direction, dir), 1.f, 1e-6f);
        Vec3 q = e.origin - c;
        // Upstream of the bounding sphere, so that every photon starts outside the scene.
        ASSERT_LT(dot(q, dir), -r);
        Vec3 lateral = q - dir * dot(q, dir);
        rho2.push_back(dot(lateral, lateral) / (r * r));  // uniform on a disc: ρ² uniform
        float x = dot(lateral, f.s), y = dot(lateral, f.t);
        hits.push_back(std::abs(x) < 0.5f * side && std::abs(y) < 0.5f * side ? power : 0.0);
    }
    test::ChiSquare chi = uniformChiSquare(rho2, 40);
    EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof));
    Moment m = moment(hits);
    EXPECT_NEAR(m.mean, E * side * side, 4 * m.stderr_);
}

TEST(LightEmission, WavelengthsFollowTheLightColour) {
    // A green box spectrum, 500–600 nm: every photon inside it, mean 550 nm, uniform.
    Spectrum green = Spectrum::fromTable({499.f, 500.f, 600.f, 601.f}, {0.f, 1.f, 1.f, 0.f});
    std::vector<std::unique_ptr<Light>> lights;
    lights.push_back(makePointLight(Vec3(0.f), 1.f, green));
    lights.push_back(makeSpotLight(Vec3(0.f), Vec3(0, 0, 1), 1.f, 10.f, 20.f, green));
    lights.push_back(makeDistantLight(Vec3(0, 0, 1), 1.f, green));
    lights.push_back(makeQuadLight(Vec3(0.f), Vec3(1, 0, 0), Vec3(0, 1, 0), 1.f, green));
    for (const auto& light : lights) {
        Sampler s(6, 0, 0);
        std::vector<double> u;
        for (int i = 0; i < 50000; ++i) {
            PhotonEmission e;
            ASSERT_TRUE(light->emitPhoton(kScene, s, &e));
            ASSERT_GE(e.lambda, 499.f);
            ASSERT_LE(e.lambda, 601.f);
            if (e.lambda >= 500.f && e.lambda < 600.f) u.push_back((e.lambda - 500.0) / 100.0);
        }
        test::ChiSquare c = uniformChiSquare(u, 20);
        EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof)) << light->describe();
    }
}

TEST(LightEmission, ZeroPowerLightsEmitNothing) {
    auto light = makePointLight(Vec3(0.f), 0.f, Spectrum(1.f));
    EXPECT_EQ(light->emittedPower(kScene), 0.f);
    Sampler s(7, 0, 0);
    PhotonEmission e;
    EXPECT_FALSE(light->emitPhoton(kScene, s, &e));
}

// The render pass's quad-light samples: irradiance at a point facing a rectangle from over its
// corner has the closed form E = L/2 [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))]
// with X = a/h, Y = b/h (the view factor of a rectangle, e.g. Howell's catalogue, C-11). The
// estimate Li cosθ must average to it at heights from 1 mm to 3 m; sampled in solid angle, Li
// itself never exceeds L Ω ≤ 2π L, even 1 mm from the light (with area sampling it reached
// L A cosθ/d², ~10⁵ L there: the speckles of a light inside a water-filled box).
TEST(LightEmission, QuadLightSamplesAreBoundedAndAverageToTheViewFactor) {
    const float a = 0.5f, b = 0.8f, power = 20.f;
    // Emitting downwards (edge_u × edge_v = −y), as a ceiling light.
    auto light = makeQuadLight(Vec3(0.f, 2.f, 0.f), Vec3(a, 0, 0), Vec3(0, 0, b), power,
                               Spectrum(1.f));
    SampledWavelengths w;
    w.lambda.fill(550.f);
    w.pdf.fill(1.f);
    const double L = power / (kPi * a * b) / double(kLambdaMax - kLambdaMin);  // W/m²/sr/nm
    for (float h : {0.001f, 0.05f, 0.5f, 3.f}) {
        const Vec3 p(0.f, 2.f - h, 0.f);  // under the corner
        const double X = a / h, Y = b / h, sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
        const double E = 0.5 * L * (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy));
        Sampler s(9, 0, 0);
        std::vector<double> est;
        double maxLi = 0;
        for (int i = 0; i < kN; ++i) {
            float u1, u2;
            s.get2D(&u1, &u2);
            LightSample ls;
            if (!light->sampleLi(p, u1, u2, w, &ls)) {
                est.push_back(0.0);
                continue;
            }
            maxLi = std::max(maxLi, double(ls.Li[0]));
            est.push_back(double(ls.Li[0]) * std::max(0.f, ls.wi.y));
        }
        const Moment m = moment(est);
        EXPECT_NEAR(m.mean, E, 4 * m.stderr_ + 1e-4 * E) << "h = " << h;
        EXPECT_LE(maxLi, 2 * kPi * L * 1.001) << "h = " << h;
        EXPECT_LT(m.stderr_, 0.01 * E) << "h = " << h;
    }
}
