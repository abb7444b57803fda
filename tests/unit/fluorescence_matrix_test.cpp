// Re-emission by an excitation–emission matrix (medium/fluorescence.h): sampled wavelengths
// follow the blend of the two rows about λi renormalised over λ ≥ λi (χ² against the table
// itself), and the reported pdf is that density; the loader reads the matrix inline or from a
// CSV file and refuses a malformed one with one line naming the key. Particles much smaller than
// the wavelength scatter with Rayleigh's cross-section (2π⁵/3) d⁶/λ⁴ ((n² − 1)/(n² + 2))², and
// the shipped sea water's CDOM fluoresces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "chi_square.h"
#include "core/rng.h"
#include "medium/fluorescence.h"
#include "medium/rayleigh_particles.h"
#include "scene/shader_loader.h"
#include "scene/toml_reader.h"
#include "test_support.h"

using namespace mirage;

namespace {

// Rows at 400 and 500 nm excitation over emission 380–700 nm, piecewise linear, 0 at both ends
// (as the loader pads a row beyond its wavelengths).
const std::vector<float> kEmission = {380, 450, 520, 600, 700};
const std::vector<float> kRowA = {0.0f, 2.0f, 1.0f, 0.2f, 0.0f};
const std::vector<float> kRowB = {0.0f, 0.3f, 1.5f, 1.5f, 0.0f};

EmissionMatrix twoRows() {
    EmissionMatrix m;
    m.excitationNm = {400.f, 500.f};
    m.rows = {Spectrum::fromTable(kEmission, kRowA), Spectrum::fromTable(kEmission, kRowB)};
    return m;
}

// The table's row at λ by linear interpolation (0 outside it): η read off the matrix directly.
double tableRow(const std::vector<float>& row, double l) {
    if (l <= kEmission.front() || l >= kEmission.back()) return 0.0;
    size_t k = 0;
    while (kEmission[k + 1] < l) ++k;
    const double t = (l - kEmission[k]) / (kEmission[k + 1] - kEmission[k]);
    return (1 - t) * row[k] + t * row[k + 1];
}

// ∫ of a row over [a, b] by the midpoint rule (the rows are piecewise linear in 1 nm steps).
double rowMass(const std::vector<float>& row, double a, double b) {
    double m = 0;
    const int n = int(std::ceil((b - a) * 20));
    for (int i = 0; i < n; ++i) m += tableRow(row, a + (i + 0.5) * (b - a) / n);
    return m * (b - a) / n;
}

// η(λi → λ) by the matrix's definition: rows normalised over 360–830, blended linearly in λi,
// restricted to λ ≥ λi and renormalised.
class ExpectedDensity {
public:
    explicit ExpectedDensity(double lambdaIn)
        : mLambdaIn(lambdaIn),
          mT(std::clamp((lambdaIn - 400.0) / 100.0, 0.0, 1.0)),
          mA(rowMass(kRowA, 360, 830)),
          mB(rowMass(kRowB, 360, 830)),
          mAllowed((1 - mT) * rowMass(kRowA, lambdaIn, 830) / mA +
                   mT * rowMass(kRowB, lambdaIn, 830) / mB) {}
    double operator()(double l) const {
        if (l < mLambdaIn) return 0.0;
        return ((1 - mT) * tableRow(kRowA, l) / mA + mT * tableRow(kRowB, l) / mB) / mAllowed;
    }

private:
    double mLambdaIn, mT, mA, mB, mAllowed;
};

}  // namespace

TEST(EmissionMatrix, SamplesFollowTheBlendOfItsRows) {
    const FluorescenceEmission e(twoRows(), false);
    for (float lambdaIn : {380.f, 430.f, 470.f, 520.f}) {
        const int n = 200000, bins = 64;
        const double lo = 360, width = (830.0 - 360) / bins;
        std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
        const ExpectedDensity expectedDensity(lambdaIn);
        Sampler s(5, uint64_t(lambdaIn), 0);
        for (int i = 0; i < n; ++i) {
            float l, pdf;
            ASSERT_TRUE(e.sample(lambdaIn, s.get1D(), &l, &pdf));
            ASSERT_GE(l, lambdaIn);
            ASSERT_NEAR(pdf, expectedDensity(l), 2e-3 * pdf + 1e-6) << lambdaIn << " " << l;
            observed[std::min(bins - 1, int((l - lo) / width))] += 1;
        }
        for (int b = 0; b < bins; ++b)
            for (int k = 0; k < 40; ++k)
                expected[b] += expectedDensity(lo + (b + (k + 0.5) / 40) * width) * width / 40 * n;
        const test::ChiSquare chi = test::chiSquare(observed, expected);
        EXPECT_LT(chi.statistic, test::chiSquareCritical(chi.dof))
            << lambdaIn << " dof " << chi.dof;
    }
    // Beyond the red end of every row nothing may be re-emitted.
    float l;
    EXPECT_FALSE(e.sample(760.f, 0.5f, &l));
    EXPECT_EQ(e.pdf(760.f, 800.f), 0.f);
}

namespace {

ShaderDesc shaderFrom(const std::string& text, const std::string& file = "eem.toml") {
    return parseShader(parseTomlText(text, file), file);
}

std::string errorOf(const std::string& text, const std::string& file = "eem.toml") {
    try {
        shaderFrom(text, file);
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

const char* kComponent = "[[component]]\nsigma_a = 1.0\nquantum_efficiency = 0.5\n";

}  // namespace

TEST(EmissionMatrix, LoadsInlineAndFromCsv) {
    const ShaderDesc inlineShader =
        shaderFrom(std::string(kComponent) +
                   "emission_matrix = { excitation = [400, 500], emission = [380, 450, 520, 600, "
                   "700], values = [[0.5, 2, 1, 0.2, 0], [0, 0.3, 1.5, 1.5, 0.5]] }\n");
    ASSERT_TRUE(inlineShader.components[0].emissionMatrix);
    EXPECT_EQ(inlineShader.components[0].emissionMatrix->rows.size(), 2u);

    const std::filesystem::path dir = test::tempDir();
    std::ofstream(dir / "cdom_eem.csv") << "ex\\em,380,450,520,600,700\n"
                                        << "# a comment\n\n"
                                        << "400,0.5,2,1,0.2,0\n500,0,0.3,1.5,1.5,0.5\n";
    const ShaderDesc csv =
        shaderFrom(std::string(kComponent) + "emission_matrix = \"cdom_eem.csv\"\n",
                   (dir / "shader.toml").string());
    ASSERT_TRUE(csv.components[0].emissionMatrix);
    const FluorescenceEmission a(*inlineShader.components[0].emissionMatrix, false),
        b(*csv.components[0].emissionMatrix, false);
    for (float l : {420.f, 500.f, 650.f}) EXPECT_EQ(a.pdf(450.f, l), b.pdf(450.f, l)) << l;

    // Malformed: one line, naming the key.
    std::ofstream(dir / "ragged.csv") << "ex,380,450\n400,1,2\n500,1\n";
    std::ofstream(dir / "word.csv") << "ex,380,450\n400,1,two\n";
    for (const std::string& bad :
         {std::string("emission_matrix = { excitation = [500, 400], emission = [380, 450], "
                      "values = [[1, 1], [1, 1]] }\n"),
          std::string("emission_matrix = { excitation = [400], emission = [380, 450], "
                      "values = [[1, 1, 1]] }\n"),
          std::string("emission_matrix = { excitation = [400], emission = [380, 450], "
                      "values = [[1, -1]] }\n"),
          std::string("emission_matrix = { excitation = [400], emission = [100, 200], "
                      "values = [[1, 1]] }\n"),
          std::string("emission_matrix = { excitation = [400], emission = [380, 450], "
                      "values = [[1, 1]] }\nemission_peak_nm = 500.0\n"),
          std::string("emission_matrix = \"ragged.csv\"\n"),
          std::string("emission_matrix = \"word.csv\"\n"),
          std::string("emission_matrix = \"missing.csv\"\n"),
          std::string("emission_matrix = 3\n")}) {
        const std::string msg = errorOf(std::string(kComponent) + bad, (dir / "s.toml").string());
        EXPECT_NE(msg.find("emission_matrix"), std::string::npos) << bad << " → " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST(RayleighParticles, CrossSectionIsRayleighs) {
    // σs = N (2π⁵/3) d⁶/λ⁴ ((n² − 1)/(n² + 2))², d = 20 nm, n = 1.5, N = 1e15 per m³.
    const double d = 20e-9, n = 1.5, N = 1e15;
    const double lorentz = (n * n - 1) / (n * n + 2);
    const ShaderDesc s = shaderFrom(
        "[[component]]\nkind = \"rayleigh\"\ndiameter_nm = 20.0\nparticle_index = 1.5\n"
        "number_density = 1e15\n");
    const MediumComponent& c = s.components[0];
    for (double lambda : {400e-9, 550e-9, 700e-9}) {
        const double published = N * 2 * std::pow(M_PI, 5) / 3 * std::pow(d, 6) /
                                 std::pow(lambda, 4) * lorentz * lorentz;
        EXPECT_NEAR(c.sigmaS(float(lambda * 1e9)), published, 1e-5 * published) << lambda;
    }
    EXPECT_EQ(c.sigmaA.maxValue(), 0.f);
    EXPECT_EQ(c.phase, PhaseKind::Rayleigh);
    EXPECT_NEAR(rayleighCrossSection(d, n, 400e-9) / rayleighCrossSection(d, n, 800e-9), 16.0,
                1e-9);
    for (const char* bad : {"number_density = -1.0\n", "diameter_nm = 20.0\n",
                            "number_density = 1e15\nsigma_s = 1.0\n"}) {
        const std::string msg = errorOf(std::string("[[component]]\nkind = \"rayleigh\"\n") + bad);
        EXPECT_NE(msg.find("eem.toml:"), std::string::npos) << bad << " → " << msg;
    }
}

TEST(SeaWater, CdomFluorescesInTheShippedShaders) {
    for (const char* name : {"sea_water", "ocean"}) {
        const ShaderDesc s = loadShader(name, "");
        bool cdom = false;
        for (const MediumComponent& c : s.components)
            if (c.kind == ComponentKind::Cdom) {
                cdom = true;
                EXPECT_NEAR(c.quantumEfficiency, 0.011f, 1e-6f) << name;
                EXPECT_EQ(c.emissionPeakNm, 450.f) << name;
            }
        EXPECT_TRUE(cdom) << name;
    }
}
