// The refractive index of air (medium/air_index.h): US Standard Atmosphere 1976 check values,
// Gladstone–Dale against the temperature law, the dispersion the paper's Cauchy b gives
// against Edlén 1966, ∇n of the stratified field against finite differences, and the inferior
// mirage: over a road 30 K hotter than the air above, a ray launched slightly downward from
// 1–10 m turns up before it reaches the ground, at the height Snell's invariant predicts.
#include <gtest/gtest.h>

#include <cmath>

#include "medium/air_index.h"
#include "transport/curved_path.h"

namespace mirage {
namespace {

// Check values from ../shared/data/README.md (h geopotential, T, P, ρ).
TEST(AirIndex, UsStandardAtmosphere1976CheckValues) {
    const AtmosphereSample a = usStandardAtmosphere1976(1450);
    EXPECT_NEAR(a.temperature, 278.725, 1e-3);
    EXPECT_NEAR(a.pressure, 85076, 1.0);
    EXPECT_NEAR(a.density, 1.0633, 1e-4);
    const AtmosphereSample b = usStandardAtmosphere1976(9800);
    EXPECT_NEAR(b.temperature, 224.450, 1e-3);
    EXPECT_NEAR(b.pressure, 27255, 1.0);
    EXPECT_NEAR(b.density, 0.42304, 1e-5);
    const AtmosphereSample c = usStandardAtmosphere1976(0);
    EXPECT_NEAR(c.density, 1.2250, 1e-4);  // the standard sea-level density
}

TEST(AirIndex, TemperatureLawIsGladstoneDaleAtConstantPressure) {
    // n − 1 ∝ ρ ∝ 1/T at fixed P: both models scale alike.
    for (double T : {250.0, 300.0, 600.0, 1200.0}) {
        const double ratioGd = (airIndex(101325, T, 550) - 1) / (airIndex(101325, 288.15, 550) - 1);
        const double ratioStam = (temperatureIndex(T) - 1) / (temperatureIndex(288.15) - 1);
        EXPECT_NEAR(ratioGd, 288.15 / T, 1e-12);
        EXPECT_NEAR(ratioStam, 288.15 / T, 1e-12);
    }
    // At the Cauchy reference state, n − 1 = a(1 + b/λ²).
    EXPECT_NEAR(airIndex(101325, 273.15, 550) - 1, 29.79e-5 * (1 + 5.67e-5 / 0.3025), 1e-12);
}

// Edlén 1966 standard air (15 °C, 101325 Pa): (n − 1)·1e8 = 8342.13 + 2406030/(130 − σ²)
// + 15997/(38.9 − σ²), σ in 1/µm.
double edlen(double lambdaNm) {
    const double s2 = 1e6 / (lambdaNm * lambdaNm);
    return 1e-8 * (8342.13 + 2406030 / (130 - s2) + 15997 / (38.9 - s2));
}

TEST(AirIndex, PrescribedCauchyBGivesAHundredthOfEdlenDispersion) {
    const double edlenRatio = edlen(400) / edlen(700);
    const double paperRatio = airRefractivity(400) / airRefractivity(700);
    const double textbookRatio = airRefractivity(400, 28.79e-5, 5.67e-3) /
                                 airRefractivity(700, 28.79e-5, 5.67e-3);
    EXPECT_NEAR(edlenRatio, 1.0252, 1e-4);
    EXPECT_NEAR(textbookRatio - 1, edlenRatio - 1, 0.1 * (edlenRatio - 1));
    EXPECT_LT(paperRatio - 1, 0.02 * (edlenRatio - 1));  // as docs/curved-light.md says
    EXPECT_NEAR(edlen(550), air::kStamN0 - 1, 1e-8);     // Stam & Languenou's n0
}

TEST(AirIndex, StratifiedGradientMatchesFiniteDifferences) {
    AtmosphereSettings s;
    s.inversions.push_back({-2.0, 0.5, 30.0, 1.0});
    s.inversions.push_back({300.0, 500.0, -8.0, 50.0});
    const AtmosphereIndexField f(s);
    for (double y : {-0.3, 0.2, 0.45, 0.9, 1.2, 5.0, 320.0, 480.0, 3000.0, 12000.0}) {
        double n;
        Vec3d g;
        f.eval(Vec3d(3, y, -2), 500, &n, &g);
        // Fourth-order central difference: n carries 1e−16 of rounding on differences of
        // ~1e−11 at a 1 mm step, and the 1 m blends curve too fast for a second-order one.
        const double e = 1e-3;
        auto at = [&](double dy) { return f.index(Vec3d(3, y + dy, -2), 500); };
        const double fd = (8 * (at(e) - at(-e)) - (at(2 * e) - at(-2 * e))) / (12 * e);
        EXPECT_NEAR(g.y, fd, 1e-4 * std::abs(fd) + 1e-14) << "y " << y;
        EXPECT_EQ(g.x, 0.0);
        EXPECT_LE(std::abs(g.y), f.gradientBound(Vec3d(0, y - 1, 0), Vec3d(0, y + 1, 0)));
    }
}

// Above the model's top (84.852 km geopotential) the air continues isothermally: the index
// stays finite and ≥ 1, falls with height, and its gradient matches finite differences. The
// top layer's lapse rate extended upwards reached 0 K near 178 km, and a distant light's
// photons (starting ~10⁸ m away) got a NaN direction there.
TEST(AirIndex, AboveTheModelTheAirIsIsothermalAndFinite) {
    const AtmosphereIndexField f{AtmosphereSettings()};
    double previous = f.index(Vec3d(0, 80000, 0), 550);
    for (double y : {90000.0, 2e5, 1e6, 5.7e7, 2e8}) {
        double n;
        Vec3d g;
        f.eval(Vec3d(1e8, y, 0), 550, &n, &g);
        ASSERT_TRUE(std::isfinite(n) && std::isfinite(g.y)) << "y " << y;
        EXPECT_GE(n, 1.0);
        EXPECT_LE(n, previous);
        EXPECT_LE(g.y, 0.0);
        previous = n;
    }
    const AtmosphereSample top = usStandardAtmosphere1976(84852), above = usStandardAtmosphere1976(1e5);
    EXPECT_DOUBLE_EQ(above.temperature, top.temperature);
    EXPECT_LT(above.pressure, top.pressure);
    const double e = 1.0;
    auto at = [&](double dy) { return f.index(Vec3d(0, 95000 + dy, 0), 550); };
    double n;
    Vec3d g;
    f.eval(Vec3d(0, 95000, 0), 550, &n, &g);
    EXPECT_NEAR(g.y, (at(e) - at(-e)) / (2 * e), 1e-3 * std::abs(g.y));
}

TEST(AirIndex, InferiorMirageTurnsRaysUpBeforeTheGround) {
    // The road heats the air: 30 K warmer up to 0.5 m, blended out over 1 m (gone by 1 m).
    AtmosphereSettings hot;
    hot.inversions.push_back({-2.0, 0.5, 30.0, 1.0});
    const AtmosphereIndexField road(hot), plain{AtmosphereSettings()};
    CurvedPathSettings set;
    set.tolerance = 1e-9;
    set.maxStep = 5;  // the hot layer is 1 m thick; long steps could straddle it unseen
    for (double h0 : {1.0, 3.0, 10.0}) {
        for (double deg : {0.1, 0.25}) {
            const double a = deg * M_PI / 180;
            const Vec3d d(std::cos(a), -std::sin(a), 0);
            double lowest = h0;
            auto track = [&](const PathState&, const PathState& b, bool) {
                lowest = std::min(lowest, b.r.y);
                return b.r.y > 0;  // the ground
            };
            const CurvedPathResult r = traceCurvedPath(road, Vec3d(0, h0, 0), d, 550,
                                                       2 * h0 / std::sin(a), set, track);
            EXPECT_FALSE(r.stopped) << "hit the road from " << h0 << " m at " << deg << "°";
            EXPECT_GT(lowest, 0.0);
            EXPECT_GT(r.end.direction().y, 0.0);
            // Snell in layers: n·cos(angle to horizontal) = v.x is conserved, so the ray turns
            // where n(y) = n(h0)·cos(a). Find that height by bisection in the hot layer.
            const double target = road.index(Vec3d(0, h0, 0), 550) * std::cos(a);
            double lo = 0, hi = 1;
            for (int i = 0; i < 60; ++i) {
                const double mid = 0.5 * (lo + hi);
                (road.index(Vec3d(0, mid, 0), 550) > target ? hi : lo) = mid;
            }
            EXPECT_NEAR(lowest, 0.5 * (lo + hi), 2e-3) << h0 << " m, " << deg << "°";
            EXPECT_NEAR(r.end.v.x, target, 1e-12);

            // Without the hot layer the same ray reaches the ground.
            lowest = h0;
            const CurvedPathResult p = traceCurvedPath(plain, Vec3d(0, h0, 0), d, 550,
                                                       2 * h0 / std::sin(a), set, track);
            EXPECT_TRUE(p.stopped);
        }
    }
}

}  // namespace
}  // namespace mirage
