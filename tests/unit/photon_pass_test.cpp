// The photon pass: deterministic for any thread count, the number of stored photons per
// emitted photon is the mean number of scattering events a/(1 − a) of a medium with no escape,
// every photon carries Φ/N, lights are chosen ∝ power, and the first-interaction and
// bounce-cap settings do exactly what they say.
#include "photon/photon_pass.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "test_support.h"

using namespace mirage;

namespace {

// A homogeneous box of side 2 m centred on the origin, σt = 50/m (100 mean free paths to a
// face). With albedo a ≤ 0.8 the diffusion length 1/√(3σaσt) ≤ 2.6 cm, so the chance that a
// photon from the centre reaches a face is ~e^{−38}: "no escape".
std::unique_ptr<Medium> thickBox(float albedo) {
    ShaderDesc s;
    s.name = "thick";
    MediumComponent c;
    c.name = "thick";
    c.sigmaA = Spectrum(50.f * (1.f - albedo));
    c.sigmaS = Spectrum(50.f * albedo);
    c.g = 0.3f;
    s.components.push_back(c);
    Bounds3 b;
    b.lo = Vec3(-1.f);
    b.hi = Vec3(1.f);
    return std::make_unique<Medium>(s, b, Transform(), 1.f);
}

PhotonPassSettings quietSettings(uint64_t photons, uint64_t seed) {
    PhotonPassSettings ps;
    ps.photons = photons;
    ps.seed = seed;
    ps.progress = Progress::Mode::Quiet;
    return ps;
}

bool samePhotons(const PhotonList& a, const PhotonList& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].p != b[i].p || a[i].wi != b[i].wi || a[i].lambda != b[i].lambda ||
            a[i].power != b[i].power)
            return false;
    return true;
}

}  // namespace

TEST(PhotonPass, SameSeedGivesTheSamePhotonsOnOneAndTwoThreads) {
    // A heterogeneous grid (density varying along x) and a homogeneous box, a point light and
    // a spot light of different colours.
    ShaderDesc smokeShader;
    smokeShader.name = "smoke";
    MediumComponent c;
    c.grid = "density";
    c.sigmaA = Spectrum(1.f);
    c.sigmaS = Spectrum::fromTable({400.f, 700.f}, {8.f, 3.f});
    c.g = 0.5f;
    smokeShader.components.push_back(c);
    std::vector<FloatGrid> grids{
        test::makeGrid([](int i, int, int) { return 0.2f + float(i) / 31.f; }, 0, 31, 1.0 / 32)};
    Medium smoke(smokeShader, std::move(grids), Transform(), 1.f, 8);
    auto fog = thickBox(0.7f);
    auto point = makePointLight(Vec3(0.5f), 10.f, blackbodyNormalized(3000.f));
    auto spot =
        makeSpotLight(Vec3(0.5f, 0.5f, 2.f), Vec3(0, 0, -1), 5.f, 10.f, 30.f, Spectrum(1.f));
    std::vector<const Light*> lights{point.get(), spot.get()};
    std::vector<const Medium*> media{&smoke, fog.get()};
    PhotonPassSettings ps = quietSettings(30000, 42);
    ps.maxBounces = 50;

    PhotonList one, two;
    PhotonPassStats s1, s2;
    {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
        one = tracePhotons(lights, media, ps, &s1);
    }
    {
        tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
        two = tracePhotons(lights, media, ps, &s2);
    }
    ASSERT_GT(one.size(), 1000u);
    EXPECT_TRUE(samePhotons(one, two));
    EXPECT_EQ(s1.stored, s2.stored);
    EXPECT_EQ(s1.cappedPaths, s2.cappedPaths);
    EXPECT_EQ(s1.emitted, 30000u);
    // Another seed gives another list.
    ps.seed = 43;
    EXPECT_FALSE(samePhotons(one, tracePhotons(lights, media, ps, nullptr)));
}

TEST(PhotonPass, StoredPhotonsPerEmittedPhotonIsTheMeanScatteringCount) {
    // With no escape, each photon scatters K times before absorption, K geometric:
    // P(K = k) = a^k (1 − a), E[K] = a/(1 − a), Var[K] = a/(1 − a)². Storing every event,
    // stored/N estimates E[K]; every photon carries Φ/N whatever happens to it.
    const float power = 20.f;
    for (float a : {0.5f, 0.8f}) {
        auto medium = thickBox(a);
        auto light = makePointLight(Vec3(0.f), power, Spectrum(1.f));
        PhotonPassSettings ps = quietSettings(40000, 7);
        ps.storeFirstInteraction = true;
        PhotonPassStats stats;
        PhotonList photons = tracePhotons({light.get()}, {medium.get()}, ps, &stats);
        const double n = double(ps.photons), expected = a / (1.0 - a);
        const double sigma = std::sqrt(a / ((1.0 - a) * (1.0 - a)) / n);
        EXPECT_NEAR(photons.size() / n, expected, 3 * sigma) << "albedo " << a;
        EXPECT_EQ(stats.stored, photons.size());
        EXPECT_EQ(stats.cappedPaths, 0u);
        const float photonPower = float(power / n);
        double total = 0;
        for (const Photon& p : photons) {
            ASSERT_EQ(p.power, photonPower);
            ASSERT_LT(length(p.p), 1.f);
            ASSERT_NEAR(length(p.wi), 1.f, 1e-5f);
            total += p.power;
        }
        // The stored power is Φ × (stored photons per emitted photon).
        EXPECT_NEAR(total, power * photons.size() / n, 1e-4 * total);
    }
}

TEST(PhotonPass, LightsAreChosenInProportionToTheirPower) {
    // Two point lights 1 m apart in a thick medium; each photon's first interaction stays
    // within a few centimetres of its light, so the share of photons nearer light A is the
    // share of emissions from A: Φ_A/(Φ_A + Φ_B) = 3/4. All photons carry (Φ_A + Φ_B)/N.
    auto medium = thickBox(0.5f);
    auto a = makePointLight(Vec3(-0.5f, 0.f, 0.f), 3.f, Spectrum(1.f));
    auto b = makePointLight(Vec3(0.5f, 0.f, 0.f), 1.f, Spectrum(1.f));
    PhotonPassSettings ps = quietSettings(20000, 9);
    ps.storeFirstInteraction = true;
    ps.maxBounces = 1;
    PhotonList photons = tracePhotons({a.get(), b.get()}, {medium.get()}, ps, nullptr);
    double nearA = 0;
    for (const Photon& p : photons) {
        nearA += p.p.x < 0.f;
        ASSERT_EQ(p.power, float(4.0 / 20000));
    }
    double share = nearA / photons.size();
    EXPECT_NEAR(share, 0.75, 3 * std::sqrt(0.75 * 0.25 / photons.size()));
}

TEST(PhotonPass, FirstInteractionAndBounceCapAreExact) {
    // The random numbers of a photon do not depend on what is stored, so the walks of three
    // runs are identical: storing all events minus storing all but the first equals the
    // number of photons that scattered at all, which a cap of one bounce stores alone.
    auto medium = thickBox(0.8f);
    auto light = makePointLight(Vec3(0.1f), 1.f, Spectrum(1.f));
    PhotonPassSettings ps = quietSettings(10000, 11);
    ps.storeFirstInteraction = true;
    PhotonPassStats all, capped;
    size_t withFirst = tracePhotons({light.get()}, {medium.get()}, ps, &all).size();
    ps.storeFirstInteraction = false;
    size_t withoutFirst = tracePhotons({light.get()}, {medium.get()}, ps, nullptr).size();
    ps.storeFirstInteraction = true;
    ps.maxBounces = 1;
    size_t firstOnly = tracePhotons({light.get()}, {medium.get()}, ps, &capped).size();
    EXPECT_EQ(withFirst - withoutFirst, firstOnly);
    // Every photon that scattered once hit the cap of one bounce.
    EXPECT_EQ(capped.cappedPaths, firstOnly);
    EXPECT_EQ(all.cappedPaths, 0u);
}

TEST(PhotonPass, NothingToTraceGivesAnEmptyList) {
    auto medium = thickBox(0.5f);
    auto dark = makePointLight(Vec3(0.f), 0.f, Spectrum(1.f));
    PhotonPassStats stats;
    EXPECT_TRUE(tracePhotons({dark.get()}, {medium.get()}, quietSettings(100, 1), &stats).empty());
    EXPECT_EQ(stats.emitted, 0u);
    EXPECT_TRUE(tracePhotons({}, {medium.get()}, quietSettings(100, 1), nullptr).empty());
}

TEST(PhotonPass, AQuadLightOnACeilingLosesNoPhotonsToIt) {
    // A 1 m² quad light lying in a black ceiling, facing a white floor 1 m below; both 200 m
    // wide. Every photon goes down, bounces off the floor (albedo 1) and is stored where it
    // hits the ceiling (albedo 0, the path ends): the stored count is the emitted count but
    // for the few that escape past the edges. A photon starting on the ceiling's plane must
    // not hit the ceiling at t ≈ 0 first. Checked for a level and a tilted ceiling (whose
    // plane's rounding goes either way at the light's points), against the same light set
    // 1 cm below the ceiling.
    for (bool tilted : {false, true}) {
        const Transform tilt = tilted ? Transform::rotate(23.0, Vec3d(1.0, 0.0, 0.3)) : Transform();
        auto at = [&](const Vec3& p) { return tilt.point(p); };
        auto along = [&](const Vec3& v) { return tilt.vector(v); };
        size_t stored[2] = {0, 0};
        for (int drop = 0; drop < 2; ++drop) {
            GeometryScene geometry;
            const int black = geometry.addMaterial(Material::diffuse("black", Spectrum(0.f)));
            const int white = geometry.addMaterial(Material::diffuse("white", Spectrum(1.f)));
            // Normals: the ceiling's edges give −y (facing down), the floor's +y.
            geometry.addQuad(at(Vec3(-100.f, 1.f, -100.f)), along(Vec3(200.f, 0.f, 0.f)),
                             along(Vec3(0.f, 0.f, 200.f)), black);
            geometry.addQuad(at(Vec3(-100.f, 0.f, -100.f)), along(Vec3(0.f, 0.f, 200.f)),
                             along(Vec3(200.f, 0.f, 0.f)), white);
            geometry.commit();
            const float y = drop ? 0.99f : 1.f;
            auto light = makeQuadLight(at(Vec3(-0.5f, y, -0.5f)), along(Vec3(1.f, 0.f, 0.f)),
                                       along(Vec3(0.f, 0.f, 1.f)), 10.f, Spectrum(1.f));
            PhotonPassStats stats;
            const PhotonMapLists maps = tracePhotonMaps({light.get()}, {}, &geometry,
                                                        quietSettings(20000, 5), &stats);
            stored[drop] = maps.surfaceGlobal.size();
        }
        std::printf("%s ceiling: %zu photons stored with the light on it, %zu 1 cm below\n",
                    tilted ? "tilted" : "level", stored[0], stored[1]);
        EXPECT_GT(stored[1], 19000u);
        // Binomial noise of a ~0.5 % escape fraction over 20 000 photons: ~10.
        EXPECT_NEAR(double(stored[0]), double(stored[1]), 60.0) << (tilted ? "tilted" : "level");
    }
}
