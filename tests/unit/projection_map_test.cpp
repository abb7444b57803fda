// Projection maps (light/projection.h, photon/projection_map.h): the unions of cones and discs
// draw the mixture density they report (χ²); each light's projection carries to every target
// the power its ordinary emission does (known answers: Φ Ω/4π, E πR², the spot's falloff over
// a cap); and the photon pass split into a main and a caustic stream keeps the caustic map's
// power, with less noise, deterministically for any thread count.
#include "photon/projection_map.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <functional>
#include <vector>

#include "chi_square.h"
#include "geometry/geometry_scene.h"
#include "light/dome_light.h"
#include "light/lamp.h"
#include "light/light.h"
#include "photon/photon_pass.h"

using namespace mirage;

namespace {

constexpr int kN = 200000;

// Pearson's χ² of samples binned by `bin` (−1: outside every bin) against the expected counts.
test::ChiSquare binnedChiSquare(int bins, const std::function<int(int)>& binOfSample,
                                const std::vector<double>& expected) {
    std::vector<double> observed(size_t(bins), 0.0);
    for (int i = 0; i < kN; ++i) {
        const int b = binOfSample(i);
        if (b >= 0) observed[size_t(b)] += 1;
    }
    return test::chiSquare(observed, expected);
}

// The first positive distance along the unit direction d from o to a sphere, or none.
bool meetsSphere(const Vec3& o, const Vec3& d, const TargetSphere& s) {
    const Vec3 oc = o - s.centre;
    const float b = dot(oc, d), c = dot(oc, oc) - s.radius * s.radius;
    const float disc = b * b - c;
    return disc >= 0.f && -b + std::sqrt(disc) > 0.f;
}

struct Estimate {
    double mean = 0, stderr_ = 0;
};

// The power N photons of a source of normalisation `power` (photon power power/N × weight)
// carry across the sphere `target`, with its standard error.
Estimate powerTo(const TargetSphere& target, double power,
                 const std::function<bool(Sampler&, PhotonEmission*)>& emit) {
    double s = 0, s2 = 0;
    for (int i = 0; i < kN; ++i) {
        Sampler sampler(7, uint64_t(i), 0);
        PhotonEmission em;
        if (!emit(sampler, &em) || !meetsSphere(em.origin, em.direction, target)) continue;
        const double x = power * em.weight;
        s += x;
        s2 += x * x;
    }
    const double m = s / kN;
    return {m, std::sqrt(std::max(0.0, s2 / kN - m * m) / kN)};
}

// Solid angle of the cone a sphere of radius R at distance d subtends.
double capSolidAngle(double d, double R) {
    return 2.0 * kPi * (1.0 - std::sqrt(d * d - R * R) / d);
}

const std::vector<TargetSphere> kTargets{
    {Vec3(0.f, 0.f, 3.f), 1.2f},   // on the axis of the spot below
    {Vec3(0.8f, 0.f, 5.f), 1.5f},  // its cone overlaps the first one's
    {Vec3(0.f, -4.f, 0.f), 0.5f},  // apart
};

Bounds3 sceneBounds() {
    Bounds3 b;
    b.lo = Vec3(-6.f);
    b.hi = Vec3(6.f);
    return b;
}

}  // namespace

TEST(ProjectionMap, ConeUnionDrawsItsMixtureDensity) {
    ConeUnion cones;
    cones.add(Vec3(0.f, 0.f, 1.f), 0.8f);
    cones.add(normalize(Vec3(0.3f, 0.f, 1.f)), 0.9f);
    cones.add(Vec3(0.f, 0.f, -1.f), 0.95f);
    // Equal-area bins in (z, φ) over the sphere; expected counts by 8 × 8 quadrature per bin.
    constexpr int nz = 64, nphi = 32, q = 8;
    std::vector<double> expected(size_t(nz * nphi), 0.0);
    const double dOmega = (2.0 / nz) * (2.0 * kPi / nphi) / (q * q);
    for (int iz = 0; iz < nz; ++iz)
        for (int ip = 0; ip < nphi; ++ip)
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b) {
                    const float z = -1.f + 2.f * (iz + (a + 0.5f) / q) / nz;
                    const float phi = 2.f * kPi * (ip + (b + 0.5f) / q) / nphi;
                    const Vec3 w = sphericalDirection(safeSqrt(1.f - z * z), z, phi);
                    expected[size_t(iz * nphi + ip)] += kN * cones.pdf(w) * dOmega;
                }
    const test::ChiSquare c = binnedChiSquare(
        nz * nphi,
        [&](int i) {
            Sampler s(11, uint64_t(i), 0);
            int coverage;
            const float pick = s.get1D(), u1 = s.get1D(), u2 = s.get1D();
            const Vec3 w = cones.sample(pick, u1, u2, &coverage);
            EXPECT_EQ(double(coverage), cones.pdf(w) * cones.solidAngleSum());
            float phi = std::atan2(w.y, w.x);
            if (phi < 0.f) phi += 2.f * kPi;
            const int iz = std::min(nz - 1, int((w.z + 1.f) * 0.5f * nz));
            return iz * nphi + std::min(nphi - 1, int(phi / (2.f * kPi) * nphi));
        },
        expected);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
    EXPECT_GT(c.dof, 250);
}

TEST(ProjectionMap, DiscUnionDrawsItsMixtureDensity) {
    const Vec3 d = normalize(Vec3(1.f, -2.f, 0.5f));
    const DiscUnion discs(
        {{Vec3(0.f), 1.f}, {Vec3(0.5f, 0.3f, 0.f), 0.6f}, {Vec3(4.f, 0, 0), 0.5f}});
    const Frame f(d);
    // The plane normal to d in the frame's (s, t), over a square holding every disc.
    constexpr int n = 48, q = 8;
    const float lo = -4.5f, size = 9.f, cell = size / n;
    std::vector<double> expected(size_t(n * n), 0.0);
    for (int iu = 0; iu < n; ++iu)
        for (int iv = 0; iv < n; ++iv)
            for (int a = 0; a < q; ++a)
                for (int b = 0; b < q; ++b) {
                    const float u = lo + cell * (iu + (a + 0.5f) / q);
                    const float v = lo + cell * (iv + (b + 0.5f) / q);
                    expected[size_t(iu * n + iv)] +=
                        kN * discs.pdf(d, f.s * u + f.t * v) * cell * cell / (q * q);
                }
    const test::ChiSquare c = binnedChiSquare(
        n * n,
        [&](int i) {
            Sampler s(13, uint64_t(i), 0);
            int coverage;
            const float pick = s.get1D(), u1 = s.get1D(), u2 = s.get1D();
            const Vec3 p = discs.sample(d, pick, u1, u2, &coverage);
            EXPECT_EQ(double(coverage), discs.pdf(d, p) * discs.areaSum());
            const int iu = int((dot(p, f.s) - lo) / cell), iv = int((dot(p, f.t) - lo) / cell);
            return iu >= 0 && iu < n && iv >= 0 && iv < n ? iu * n + iv : -1;
        },
        expected);
    EXPECT_LT(c.statistic, test::chiSquareCritical(c.dof));
    EXPECT_GT(c.dof, 100);
}

TEST(ProjectionMap, PointLightCarriesItsShareToEveryTarget) {
    constexpr float kPower = 100.f;
    const auto lamp = makePointLight(Vec3(0.f), kPower, Spectrum(1.f));
    const auto map = lamp->projection({kTargets, sceneBounds()});
    ASSERT_TRUE(map);
    for (const TargetSphere& t : kTargets) {
        const Estimate e = powerTo(
            t, map->power(), [&](Sampler& s, PhotonEmission* em) { return map->emit(s, em); });
        const double expected = kPower * capSolidAngle(length(t.centre), t.radius) / (4.0 * kPi);
        EXPECT_NEAR(e.mean, expected, 4.0 * e.stderr_ + 1e-4 * expected);
    }
}

TEST(ProjectionMap, SpotLightCarriesItsFalloffOverTheTargetsCap) {
    // Inner 20°, outer 30° about +z: the first target's cone (23.6°) reaches into the falloff,
    // the third lies outside the spot and gets nothing.
    constexpr float kPower = 100.f;
    const auto spot =
        makeSpotLight(Vec3(0.f), Vec3(0.f, 0.f, 1.f), kPower, 20.f, 30.f, Spectrum(1.f));
    const auto map = spot->projection({kTargets, sceneBounds()});
    ASSERT_TRUE(map);
    const double ci = std::cos(radians(20.f)), co = std::cos(radians(30.f));
    const double omegaF = 2.0 * kPi * (1.0 - 0.5 * (ci + co));
    // ∫ f dω over the first target's cap: 2π ∫ f(cos θ) d cos θ, by the midpoint rule.
    const double cosCap = std::sqrt(9.0 - 1.2 * 1.2) / 3.0;
    double integral = 0.0;
    constexpr int steps = 100000;
    for (int i = 0; i < steps; ++i) {
        const double c = cosCap + (1.0 - cosCap) * (i + 0.5) / steps;
        const double t = std::clamp((c - co) / (ci - co), 0.0, 1.0);
        integral += t * t * (3.0 - 2.0 * t);
    }
    integral *= 2.0 * kPi * (1.0 - cosCap) / steps;
    const auto emit = [&](Sampler& s, PhotonEmission* em) { return map->emit(s, em); };
    const Estimate first = powerTo(kTargets[0], map->power(), emit);
    EXPECT_NEAR(first.mean, kPower * integral / omegaF, 4.0 * first.stderr_);
    EXPECT_EQ(powerTo(kTargets[2], map->power(), emit).mean, 0.0);
}

TEST(ProjectionMap, SphereLightAndDistantLightAndDomeMatchTheirOrdinaryEmission) {
    constexpr float kIrradiance = 3.f;
    LampDesc sphere;
    sphere.position = Vec3(0.f, 1.f, -1.f);
    sphere.radius = 0.4f;
    sphere.powerW = 50.f;
    const auto sphereLamp = makeLamp(sphere, Spectrum(1.f));
    const auto sun =
        makeDistantLight(normalize(Vec3(0.2f, -1.f, 0.3f)), kIrradiance, Spectrum(1.f));
    const auto dome = makeDomeLight(Spectrum(0.01f), DomeSettings{});
    const Bounds3 b = sceneBounds();
    for (const Light* light : {sphereLamp.get(), sun.get(), dome.get()}) {
        const auto map = light->projection({kTargets, b});
        ASSERT_TRUE(map) << light->describe();
        for (const TargetSphere& t : kTargets) {
            const Estimate projected = powerTo(
                t, map->power(), [&](Sampler& s, PhotonEmission* em) { return map->emit(s, em); });
            const Estimate ordinary = powerTo(
                t, light->emittedPower(b),
                [&](Sampler& s, PhotonEmission* em) { return light->emitPhoton(b, s, em); });
            const double sigma = std::hypot(projected.stderr_, ordinary.stderr_);
            EXPECT_NEAR(projected.mean, ordinary.mean, 4.0 * sigma) << light->describe();
            // The projection's photons all head for the targets: far less noise.
            EXPECT_LT(projected.stderr_, 0.5 * ordinary.stderr_) << light->describe();
        }
    }
    // Known answers for light at infinity: E πR² through each target, and for the constant dome
    // (∫∫ L dω dλ) πR² (its photons cross each disc from every direction).
    for (const TargetSphere& t : kTargets) {
        const auto map = sun->projection({kTargets, b});
        const Estimate e = powerTo(
            t, map->power(), [&](Sampler& s, PhotonEmission* em) { return map->emit(s, em); });
        const double expected = kIrradiance * kPi * t.radius * t.radius;
        EXPECT_NEAR(e.mean, expected, 4.0 * e.stderr_ + 1e-4 * expected);
    }
}

namespace {

// A glass ball under a point light, over a white floor: caustic photons land on the floor
// through the ball, which takes ~1.6 % of the light's photons.
struct CausticScene {
    GeometryScene geometry;
    std::unique_ptr<Light> light = makePointLight(Vec3(0.f, 3.f, 0.f), 100.f, Spectrum(1.f));
    CausticScene() {
        const int glass = geometry.addMaterial(Material::dielectric("glass", 1.5f));
        const int white = geometry.addMaterial(Material::diffuse("white", Spectrum(0.8f)));
        geometry.addSphere(Vec3(0.f, 1.f, 0.f), 0.5f, glass);
        geometry.addQuad(Vec3(-3.f, 0.f, 3.f), Vec3(6.f, 0.f, 0.f), Vec3(0.f, 0.f, -6.f), white);
        geometry.commit();
    }
    PhotonMapLists trace(uint64_t photons, bool projection, PhotonPassStats* stats) const {
        PhotonPassSettings ps;
        ps.photons = photons;
        ps.seed = 5;
        ps.progress = Progress::Mode::Quiet;
        ps.projection =
            projection ? PhotonPassSettings::Projection::On : PhotonPassSettings::Projection::Off;
        return tracePhotonMaps({light.get()}, {}, &geometry, ps, stats);
    }
};

// Σ power of a list and its standard error: a path stores at most one caustic photon (its
// first diffuse hit), so the stored powers are independent and Var Σ ≤ Σ p².
Estimate total(const PhotonList& list) {
    double s = 0, s2 = 0;
    for (const Photon& p : list) {
        s += p.power;
        s2 += double(p.power) * p.power;
    }
    return {s, std::sqrt(s2)};
}

}  // namespace

TEST(ProjectionMap, CausticStreamKeepsTheCausticMapsPowerWithLessNoise) {
    const CausticScene scene;
    PhotonPassStats on, off;
    const PhotonMapLists withMaps = scene.trace(100000, true, &on);
    const PhotonMapLists without = scene.trace(400000, false, &off);
    EXPECT_EQ(on.emitted, 200000u);  // the main stream and as many caustic photons
    EXPECT_EQ(off.emitted, 400000u);
    const Estimate a = total(withMaps.surfaceCaustic), b = total(without.surfaceCaustic);
    ASSERT_GT(without.surfaceCaustic.size(), 1000u);
    EXPECT_NEAR(a.mean, b.mean, 4.0 * std::hypot(a.stderr_, b.stderr_));
    // The error falls as 1/√(caustic paths) and with the photons' power: by √(400 000 × 1.6 % /
    // 100 000) ≈ 0.25 (0.254 measured), the caustic photons' density times 16.
    EXPECT_LT(a.stderr_, 0.3 * b.stderr_);
    // The global map (light that met the floor, then the ball) sums the same power both ways
    // too; its paths store a photon or two each, so 5 of the error bound above.
    const Estimate g1 = total(withMaps.surfaceGlobal), g2 = total(without.surfaceGlobal);
    EXPECT_NEAR(g1.mean, g2.mean, 5.0 * std::hypot(g1.stderr_, g2.stderr_));
}

TEST(ProjectionMap, TwoStreamsGiveTheSamePhotonsOnOneAndTwoThreads) {
    const CausticScene scene;
    PhotonMapLists one, two;
    {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
        one = scene.trace(20000, true, nullptr);
    }
    {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
        two = scene.trace(20000, true, nullptr);
    }
    ASSERT_GT(one.surfaceCaustic.size(), 1000u);
    for (auto list : {&PhotonMapLists::surfaceCaustic, &PhotonMapLists::surfaceGlobal}) {
        ASSERT_EQ((one.*list).size(), (two.*list).size());
        for (size_t i = 0; i < (one.*list).size(); ++i) {
            EXPECT_EQ((one.*list)[i].p, (two.*list)[i].p);
            EXPECT_EQ((one.*list)[i].power, (two.*list)[i].power);
        }
    }
}

TEST(ProjectionMap, ASpotAimedAtTheGlassAndNoSpecularShapesHaveNoMaps) {
    const CausticScene scene;
    const Bounds3 b = scene.geometry.bounds();
    // The spot's 10° cone lies inside the ball's (asin(0.5/2) = 14.5°): its photons are the
    // caustic photons already.
    const auto spot =
        makeSpotLight(Vec3(0.f, 3.f, 0.f), Vec3(0.f, -1.f, 0.f), 10.f, 8.f, 10.f, Spectrum(1.f));
    EXPECT_FALSE(planProjection({spot.get()}, &scene.geometry, b, true).any());
    EXPECT_TRUE(planProjection({scene.light.get()}, &scene.geometry, b, true).any());
    EXPECT_FALSE(planProjection({scene.light.get()}, &scene.geometry, b, false).any());
    GeometryScene diffuseOnly;
    const int white = diffuseOnly.addMaterial(Material::diffuse("white", Spectrum(0.8f)));
    diffuseOnly.addSphere(Vec3(0.f, 1.f, 0.f), 0.5f, white);
    diffuseOnly.commit();
    const ProjectionPlan none = planProjection({scene.light.get()}, &diffuseOnly, b, true);
    EXPECT_EQ(none.targets, 0u);
    EXPECT_FALSE(none.any());
}
