// The component laws (medium/component.h): each kind's coefficients against its published
// closed form, its bound against its coefficients over every wavelength and a range of
// concentrations, its per-path lookup and dense spectrum against its single-wavelength answer,
// its optical depth from ray integrals against σt · length, and its linearity flags. Then the
// medium's grid slots: resolved to indices once, and a slot without a grid refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "medium/component.h"
#include "medium/medium.h"
#include "medium/ocean_components.h"
#include "spectrum/ocean_spectra.h"
#include "test_support.h"

using namespace mirage;

namespace {

MediumComponent linearGrey() {
    MediumComponent c;
    c.name = "smoke";
    c.sigmaA = Spectrum(0.3f);
    c.sigmaS = Spectrum(1.2f);
    return c;
}

// σa falling and σs rising with λ, linearly between 360 and 830 nm.
MediumComponent linearSpectral() {
    MediumComponent c;
    c.name = "dust";
    std::vector<float> a(Spectrum::kDenseSamples), s(Spectrum::kDenseSamples);
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        a[size_t(i)] = 2.f - float(i) / 470.f;
        s[size_t(i)] = 0.5f + float(i) / 470.f;
    }
    c.sigmaA = Spectrum::fromDense(std::move(a));
    c.sigmaS = Spectrum::fromDense(std::move(s));
    return c;
}

MediumComponent water() {
    MediumComponent c;
    c.name = "water";
    makeWater(&c);
    return c;
}

MediumComponent cdom() {
    MediumComponent c;
    c.name = "cdom";
    makeCdom(&c, ocean::kCdomSlope);
    return c;
}

MediumComponent chlorophyll() {
    MediumComponent c;
    c.name = "chlorophyll";
    makeChlorophyll(&c);
    return c;
}

std::vector<MediumComponent> everyKind() {
    return {linearGrey(), linearSpectral(), water(), cdom(), chlorophyll()};
}

float sigmaT(const ComponentModel& m, float C, float lambda) {
    return m.sigmaA(C, lambda) + m.sigmaS(C, lambda);
}

// max_λ σa + max_λ σs at concentration C, every whole nanometre: what a bound over λ may reach
// when the two maxima lie at different wavelengths.
float sumOfMaxima(const ComponentModel& m, float C) {
    float a = 0.f, s = 0.f;
    for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
        a = std::max(a, m.sigmaA(C, kLambdaMin + float(i)));
        s = std::max(s, m.sigmaS(C, kLambdaMin + float(i)));
    }
    return a + s;
}

double relErr(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-30); }

}  // namespace

TEST(ComponentModel, LinearityAndGreyFlagsFollowTheKind) {
    EXPECT_TRUE(ComponentModel::make(linearGrey())->linear());
    EXPECT_TRUE(ComponentModel::make(linearGrey())->grey());
    EXPECT_TRUE(ComponentModel::make(linearSpectral())->linear());
    EXPECT_FALSE(ComponentModel::make(linearSpectral())->grey());
    EXPECT_TRUE(ComponentModel::make(water())->linear());
    EXPECT_FALSE(ComponentModel::make(water())->grey());
    EXPECT_TRUE(ComponentModel::make(cdom())->linear());
    EXPECT_FALSE(ComponentModel::make(cdom())->grey());
    EXPECT_FALSE(ComponentModel::make(chlorophyll())->linear());
    EXPECT_FALSE(ComponentModel::make(chlorophyll())->grey());
}

TEST(ComponentModel, CoefficientsAreThePublishedLaws) {
    auto grey = ComponentModel::make(linearGrey());
    auto spectral = ComponentModel::make(linearSpectral());
    auto w = ComponentModel::make(water());
    auto y = ComponentModel::make(cdom());
    auto chl = ComponentModel::make(chlorophyll());
    for (float l = kLambdaMin; l <= kLambdaMax; l += 7.f) {
        for (float C : {0.05f, 0.7f, 3.f, 20.f}) {
            EXPECT_FLOAT_EQ(grey->sigmaA(C, l), 0.3f * C);
            EXPECT_FLOAT_EQ(grey->sigmaS(C, l), 1.2f * C);
            const double x = (l - kLambdaMin) / 470.0;
            EXPECT_NEAR(spectral->sigmaA(C, l), C * (2.0 - x), 1e-5 * C);
            EXPECT_NEAR(spectral->sigmaS(C, l), C * (0.5 + x), 1e-5 * C);
            // Sea water (Pope & Fry 1997 absorption, Morel 1974 scattering), C in units of water.
            const double bw = C * 0.00288 * std::pow(l / 500.0, -4.32);
            EXPECT_NEAR(w->sigmaA(C, l), C * ocean::waterAbsorption()(l), 1e-6 * C);
            EXPECT_LT(relErr(w->sigmaS(C, l), bw), 2e-3) << l << " nm";
            // CDOM: C = a_y(440) in 1/m, exponential in λ, no scattering.
            EXPECT_LT(relErr(y->sigmaA(C, l), C * std::exp(-0.014 * (l - 440.0))), 1e-4) << l;
            EXPECT_EQ(y->sigmaS(C, l), 0.f);
            // Chlorophyll at C mg/m³: Bricaud et al. 1995, Gordon & Morel 1983.
            const double aph = ocean::bricaudA()(l) * std::pow(C, 1.0 - ocean::bricaudB()(l));
            const double bp = 0.30 * std::pow(C, 0.62) * 550.0 / l;
            EXPECT_LT(relErr(chl->sigmaA(C, l), aph), 1e-4) << l << " nm, C " << C;
            EXPECT_LT(relErr(chl->sigmaS(C, l), bp), 2e-3) << l << " nm, C " << C;
        }
        EXPECT_EQ(chl->sigmaA(0.f, l), 0.f);
        EXPECT_EQ(chl->sigmaS(0.f, l), 0.f);
    }
}

TEST(ComponentModel, BoundCoversSigmaTAtEveryWavelengthAndLowerConcentration) {
    for (const MediumComponent& c : everyKind()) {
        auto m = ComponentModel::make(c);
        double previous = 0.0;
        for (float cMax : {1e-3f, 0.1f, 1.f, 10.f, 300.f}) {
            const double bound = m->sigmaTBound(double(cMax));
            EXPECT_GE(bound, previous) << c.name << ": the bound grows with C";
            previous = bound;
            for (int k = 0; k <= 40; ++k) {
                const float C = k == 0 ? cMax : float(cMax * std::pow(1e-4, k / 40.0));
                for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
                    const float l = kLambdaMin + float(i);
                    // The bound is exact arithmetic; σt itself is rounded to float.
                    ASSERT_LE(sigmaT(*m, C, l), bound * (1.0 + 1e-6))
                        << c.name << " at C " << C << ", " << l << " nm";
                }
            }
            // A bound, not a wild one.
            EXPECT_LT(bound, 1.01 * sumOfMaxima(*m, cMax)) << c.name << " at C " << cMax;
        }
    }
}

TEST(ComponentModel, MajorantCellsBoundTheirLargestConcentration) {
    const float k = 2.5f, v = 1.6f;  // concentration × density scale, grid value
    FloatGrid grid = test::makeGrid([&](int, int, int) { return v; }, 0, 7, 0.125);
    for (const MediumComponent& c : everyKind()) {
        auto m = ComponentModel::make(c);
        MajorantGrid constant(grid.objectBounds(), 1), gridded(grid.objectBounds(), 4);
        m->addToMajorant(&constant, nullptr, k);
        m->addToMajorant(&gridded, &grid, k);
        float atK = 0.f, atKv = 0.f;
        for (int i = 0; i < Spectrum::kDenseSamples; ++i) {
            atK = std::max(atK, sigmaT(*m, k, kLambdaMin + float(i)));
            atKv = std::max(atKv, sigmaT(*m, k * v, kLambdaMin + float(i)));
        }
        EXPECT_GE(constant.cell(0, 0, 0), atK) << c.name;
        EXPECT_LT(constant.cell(0, 0, 0), 1.01f * sumOfMaxima(*m, k)) << c.name;
        for (int x = 0; x < gridded.res(0); ++x)
            for (int y = 0; y < gridded.res(1); ++y)
                for (int z = 0; z < gridded.res(2); ++z)
                    EXPECT_GE(gridded.cell(x, y, z), atKv) << c.name;
    }
}

TEST(ComponentModel, PathLookupAndDenseSpectrumMatchTheSingleWavelengthAnswer) {
    Sampler s(7, 0, 0);
    for (const MediumComponent& c : everyKind()) {
        auto m = ComponentModel::make(c);
        for (int trial = 0; trial < 20; ++trial) {
            const SampledWavelengths w = SampledWavelengths::sampleVisible(s.get1D());
            const float k = 0.5f + 3.f * s.get1D(), v = 0.01f + 4.f * s.get1D();
            PathCoefficients pc;
            m->sampleWavelengths(w, k, &pc);
            SampledSpectrum sigmaA(0.25f), sigmaS(7.f);
            m->evalPath(pc, v, &sigmaA, &sigmaS);
            for (int j = 0; j < kSpectrumSamples; ++j) {
                // evalPath adds σa and overwrites σs.
                EXPECT_LT(relErr(sigmaA[j] - 0.25f, m->sigmaA(k * v, w.lambda[j])), 1e-4)
                    << c.name << " at " << w.lambda[j] << " nm";
                EXPECT_LT(relErr(sigmaS[j], m->sigmaS(k * v, w.lambda[j])), 1e-5)
                    << c.name << " at " << w.lambda[j] << " nm";
            }
        }
        std::vector<float> dense(Spectrum::kDenseSamples);
        m->sigmaADense(1.7f, dense.data());
        for (int i = 0; i < Spectrum::kDenseSamples; ++i)
            EXPECT_LT(relErr(dense[size_t(i)], m->sigmaA(1.7f, kLambdaMin + float(i))), 1e-5)
                << c.name << " at " << kLambdaMin + float(i) << " nm";
    }
}

TEST(ComponentModel, OpticalDepthOfAConstantConcentrationIsSigmaTTimesLength) {
    const float length = 2.f;
    for (const MediumComponent& c : everyKind()) {
        auto m = ComponentModel::make(c);
        const std::vector<float> powers = m->depthPowers();
        ASSERT_FALSE(powers.empty());
        if (m->linear()) {
            EXPECT_EQ(powers, std::vector<float>{1.f}) << c.name;
        }
        // Within the concentrations the power-law interpolation is documented for.
        for (float C : {0.05f, 0.4f, 2.f, 20.f}) {
            std::vector<float> zero(powers.size(), 0.f), integral;
            for (float p : powers) integral.push_back(std::pow(C, p) * length);
            for (float l = kLambdaMin; l <= kLambdaMax; l += 5.f) {
                const double expected = double(sigmaT(*m, C, l)) * length;
                const float tau = m->opticalDepth(l, {zero.data(), integral.data(), 1.f});
                EXPECT_LT(relErr(tau, expected), 5e-4) << c.name << " C " << C << ", " << l;
                // Halfway between the nodes, half the depth.
                const float half = m->opticalDepth(l, {zero.data(), integral.data(), 0.5f});
                EXPECT_LT(relErr(half, 0.5 * expected), 5e-4) << c.name;
            }
        }
    }
}

namespace {

// Components on "density" (twice) and "soot", a constant one, emission from "temperature":
// gridSlots() = density, soot, temperature.
ShaderDesc slottedShader() {
    ShaderDesc s;
    s.name = "slotted";
    MediumComponent a = linearGrey(), b = linearGrey(), soot = linearGrey(), air = linearGrey();
    a.grid = "density";
    soot.grid = "soot";
    b.grid = "density";
    air.concentration = 0.01f;
    s.components = {a, soot, air, b};
    EmissionSpec e;
    e.temperatureGrid = "temperature";
    s.emission = e;
    return s;
}

std::vector<FloatGrid> grids(const std::vector<std::string>& names) {
    std::vector<FloatGrid> out;
    for (const auto& n : names)
        out.push_back(test::makeGrid([](int, int, int) { return 1.f; }, 0, 3, 0.25, Vec3d(0.0), n));
    return out;
}

}  // namespace

TEST(MediumSlots, ResolvedToGridIndicesWhenTheMediumIsBuilt) {
    Medium m(slottedShader(), grids({"d", "s", "t"}), Transform(), 1.f, 4);
    EXPECT_EQ(m.binding().componentSlot(0), 0);
    EXPECT_EQ(m.binding().componentSlot(1), 1);
    EXPECT_EQ(m.binding().componentSlot(2), -1);
    EXPECT_EQ(m.binding().componentSlot(3), 0);
    EXPECT_EQ(m.binding().temperatureSlot(), 2);
    EXPECT_TRUE(m.binding().componentModel(0).linear());

    ShaderDesc noEmission = slottedShader();
    noEmission.emission.reset();
    Medium plain(noEmission, grids({"d", "s"}), Transform(), 1.f, 4);
    EXPECT_EQ(plain.binding().temperatureSlot(), -1);
}

TEST(MediumSlots, ASlotWithoutAGridIsRefusedByName) {
    try {
        Medium m(slottedShader(), grids({"d", "s"}), Transform(), 1.f, 4);
        FAIL() << "a shader reading three slots was built from two grids";
    } catch (const MirageError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("slotted"), std::string::npos) << what;
        EXPECT_NE(what.find("no grid for 'temperature'"), std::string::npos) << what;
    }
    ShaderDesc unnamed = slottedShader();
    unnamed.emission->temperatureGrid = "";
    try {
        Medium m(unnamed, grids({"d", "s"}), Transform(), 1.f, 4);
        FAIL() << "an emission without a temperature slot was accepted";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("temperature"), std::string::npos) << e.what();
    }
}

TEST(MediumSlots, TheBindingAloneNamesEachComponentsGrid) {
    const ShaderBinding b(slottedShader(), grids({"d", "s", "t"}), 2.f);
    EXPECT_EQ(b.componentGrid(0), &b.grids()[0]);
    EXPECT_EQ(b.componentGrid(1), &b.grids()[1]);
    EXPECT_EQ(b.componentGrid(2), nullptr);  // the constant component reads no grid
    EXPECT_EQ(b.componentGrid(3), &b.grids()[0]);
    EXPECT_EQ(b.grids()[size_t(b.temperatureSlot())].name(), "t");
    EXPECT_EQ(b.densityScale(), 2.f);
    EXPECT_EQ(b.shader().name, "slotted");
}
