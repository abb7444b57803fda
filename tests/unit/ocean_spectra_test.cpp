// Embedded ocean spectra against the full published tables in ../shared/data/spectra: the
// embedded step must reproduce every published row within the interpolation error stated in
// ocean_spectra.cpp (measured there: water 4.8 %, Bricaud A 3.9 %, B 0.0065 absolute).
#include "spectrum/ocean_spectra.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "test_support.h"

using namespace mirage;

namespace {

// Rows of numbers from a text table; lines that do not start with a number are comments.
std::vector<std::vector<double>> readRows(const std::string& path) {
    std::vector<std::vector<double>> rows;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream ss(line);
        std::vector<double> row;
        double v;
        while (ss >> v) row.push_back(v);
        if (row.size() >= 2) rows.push_back(row);
    }
    return rows;
}

}  // namespace

TEST(OceanSpectra, WaterAbsorptionMatchesPopeFryWithinInterpolationError) {
    MIRAGE_REQUIRE_SHARED(path, "spectra/water_absorption_pope_fry_1997.txt");
    auto rows = readRows(path);
    ASSERT_GT(rows.size(), 100u);
    double worst = 0.0;
    for (const auto& r : rows) {
        if (r[0] < kLambdaMin) continue;  // the spectrum starts at 360 nm
        double rel = std::abs(ocean::waterAbsorption()(float(r[0])) - r[1]) / r[1];
        worst = std::max(worst, rel);
        EXPECT_LT(rel, 0.05) << r[0] << " nm";
    }
    std::printf("water absorption: max relative error %.4f\n", worst);
}

TEST(OceanSpectra, BricaudMatchesTable2WithinInterpolationError) {
    MIRAGE_REQUIRE_SHARED(path, "spectra/chlorophyll_specific_absorption_bricaud_1995.txt");
    auto rows = readRows(path);
    ASSERT_EQ(rows.size(), 76u);
    double worstA = 0.0, worstB = 0.0, worstAph = 0.0;
    for (const auto& r : rows) {
        float l = float(r[0]);
        float A = ocean::bricaudA()(l), B = ocean::bricaudB()(l);
        worstA = std::max(worstA, std::abs(A - r[1]) / r[1]);
        worstB = std::max(worstB, std::abs(B - r[2]));
        for (float chl : {0.05f, 1.f, 10.f}) {
            double ref = r[1] * std::pow(chl, 1.0 - r[2]);
            worstAph = std::max(
                worstAph, std::abs(ocean::phytoplanktonAbsorption(A, B, chl) - ref) / ref);
        }
    }
    EXPECT_LT(worstA, 0.04);
    EXPECT_LT(worstB, 0.007);
    EXPECT_LT(worstAph, 0.06);
    std::printf("Bricaud: max error A %.4f (relative), B %.4f, a_ph %.4f (relative)\n", worstA,
                worstB, worstAph);
}

TEST(OceanSpectra, EmbeddedRowsAreExactAtTheirWavelengths) {
    auto t = ocean::waterAbsorptionTable();
    for (int i = 0; i < t.size; ++i) {
        if (t.rows[i].lambdaNm < kLambdaMin) continue;
        EXPECT_NEAR(ocean::waterAbsorption()(t.rows[i].lambdaNm), t.rows[i].a,
                    1e-6f * t.rows[i].a);
    }
    EXPECT_FLOAT_EQ(ocean::bricaudA()(675.f), 0.0201f);
    EXPECT_FLOAT_EQ(ocean::bricaudB()(440.f), 0.332f);
}

TEST(OceanSpectra, AnalyticLaws) {
    EXPECT_FLOAT_EQ(ocean::waterScattering(500.f), 0.00288f);
    // λ^−4.32: halving the wavelength multiplies b_w by 2^4.32 ≈ 19.97.
    EXPECT_NEAR(ocean::waterScattering(400.f) / ocean::waterScattering(800.f), 19.97, 0.01);
    EXPECT_NEAR(ocean::waterScatteringSpectrum()(450.f), ocean::waterScattering(450.f), 1e-7);
    EXPECT_FLOAT_EQ(ocean::cdomShape(440.f), 1.f);
    EXPECT_NEAR(ocean::cdomShape(540.f), std::exp(-1.4), 1e-6);
    EXPECT_NEAR(ocean::particleScatteringPerUnit(550.f), 0.30f, 1e-7);
    EXPECT_FLOAT_EQ(ocean::phytoplanktonAbsorption(0.04f, 0.3f, 0.f), 0.f);
}
