// Shader files with component kinds: the built-in ocean shader, what each kind accepts, and
// the errors for keys a kind does not take.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "core/error.h"
#include "film/color.h"
#include "medium/ocean_components.h"
#include "scene/scene.h"
#include "scene/shader_loader.h"
#include "test_support.h"

using namespace mirage;

namespace {

std::string parseError(const std::string& text) {
    try {
        parseShader(parseTomlText(text, "test.toml"), "test.toml");
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(OceanShader, BuiltInOceanHasWaterChlorophyllAndCdom) {
    ShaderDesc s = loadShader("ocean", "");
    ASSERT_EQ(s.components.size(), 3u);
    EXPECT_EQ(s.components[0].kind, ComponentKind::Water);
    EXPECT_EQ(s.components[0].phase, PhaseKind::Water);
    EXPECT_EQ(s.components[1].kind, ComponentKind::Chlorophyll);
    EXPECT_EQ(s.components[1].grid, "chlorophyll");
    EXPECT_FLOAT_EQ(s.components[1].g, 0.924f);
    EXPECT_FLOAT_EQ(s.components[1].quantumEfficiency, 0.02f);
    EXPECT_FLOAT_EQ(s.components[1].emissionPeakNm, 685.f);
    EXPECT_EQ(s.components[2].kind, ComponentKind::Cdom);
    EXPECT_NEAR(s.components[2].sigmaA(540.f), std::exp(-1.4f), 1e-5f);
    EXPECT_TRUE(s.spectralCoefficients());
    EXPECT_TRUE(s.fluorescent());
    EXPECT_EQ(s.gridSlots(), std::vector<std::string>{"chlorophyll"});
}

TEST(OceanShader, KindsAndTheirKeys) {
    ShaderDesc s = parseShader(parseTomlText(R"(
[[component]]
kind = "cdom"
concentration = 0.3
slope = 0.017
quantum_efficiency = 0.01
emission_peak_nm = 450
emission_fwhm_nm = 80
anti_stokes = true

[[component]]
sigma_a = 0.1
sigma_s = 0.2
phase = "water"
)",
                                             "test.toml"),
                               "test.toml");
    ASSERT_EQ(s.components.size(), 2u);
    EXPECT_NEAR(s.components[0].sigmaA(540.f), std::exp(-1.7f), 1e-5f);
    EXPECT_TRUE(s.components[0].antiStokes);
    EXPECT_FLOAT_EQ(s.components[0].emissionFwhmNm, 80.f);
    EXPECT_EQ(s.components[1].kind, ComponentKind::Linear);
    EXPECT_EQ(s.components[1].phase, PhaseKind::Water);
    ShaderDesc grey;
    grey.components = {s.components[1]};
    EXPECT_FALSE(grey.spectralCoefficients());
}

TEST(OceanShader, ErrorsNameTheKey) {
    std::string msg = parseError("[[component]]\nkind = \"water\"\nsigma_a = 1.0\n");
    EXPECT_NE(msg.find("sigma_a"), std::string::npos) << msg;
    msg = parseError("[[component]]\nkind = \"plasma\"\n");
    EXPECT_NE(msg.find("chlorophyll"), std::string::npos) << msg;
    EXPECT_NE(msg.find("test.toml:2"), std::string::npos) << msg;
    msg = parseError("[[component]]\nkind = \"chlorophyll\"\nquantum_efficiency = 1.5\n");
    EXPECT_NE(msg.find("quantum_efficiency"), std::string::npos) << msg;
    msg = parseError("[[component]]\nphase = \"mie\"\n");
    EXPECT_NE(msg.find("phase"), std::string::npos) << msg;
}

TEST(OceanShader, InfoReportsSpectralTransportAndFluorescence) {
    // "Model only what a scene requires": the ocean turns on spectral coefficients (its kinds)
    // and fluorescence (its Γ); smoke turns on neither.
    std::string dir = test::tempDir(), out;
    ASSERT_EQ(
        0, test::runMirage("make-asset fog-sphere -o '" + dir + "/fog.vdb' --resolution 16", &out))
        << out;
    auto physics = [&](const std::string& volume) {
        std::ofstream(dir + "/s.toml") << "[[volume]]\nfile = \"fog.vdb\"\n"
                                       << volume
                                       << "\n[[light]]\ntype = \"distant\"\n"
                                          "direction = [0, -1, 0]\nirradiance = 100.0\n";
        ColorPipeline color;
        Scene scene = loadScene(dir + "/s.toml", LoadOptions{}, color);
        std::map<std::string, PhysicsTerm> terms;
        for (const auto& t : scene.physics()) terms[t.name] = t;
        return terms;
    };
    auto ocean = physics("shader = \"ocean\"\nbind = { chlorophyll = \"density\" }\n");
    EXPECT_TRUE(ocean["spectral coefficients"].active);
    EXPECT_NE(ocean["spectral coefficients"].why.find("kind water"), std::string::npos)
        << ocean["spectral coefficients"].why;
    EXPECT_TRUE(ocean["fluorescence"].active);
    EXPECT_NE(ocean["fluorescence"].why.find("0.02"), std::string::npos)
        << ocean["fluorescence"].why;
    auto smoke = physics("shader = \"smoke\"\n");
    EXPECT_FALSE(smoke["spectral coefficients"].active);
    EXPECT_FALSE(smoke["fluorescence"].active);
}

// Case-1 water's yellow substance follows the chlorophyll as in Morel & Maritorena (2001):
// a_y(440) = 0.2 [a_w(440) + 0.06 Chl^0.65], a_w(440) = 0.00635 1/m (Pope & Fry 1997), slope
// 0.014 1/nm. The loader's expansion of `covaries_with` (a constant term and a power law of the
// chlorophyll) must add up to the published closed form at every concentration.
TEST(OceanShader, Case1CdomFollowsMorelAndMaritorena) {
    ShaderDesc s = loadShader("sea_water", "");
    applyCase1Cdom(&s);
    const MediumComponent *constant = nullptr, *power = nullptr, *chl = nullptr;
    for (const auto& c : s.components) {
        if (c.name == "cdom") constant = &c;
        if (c.name == "cdom_chl") power = &c;
        if (c.name == "chlorophyll") chl = &c;
    }
    ASSERT_TRUE(constant && power && chl);
    EXPECT_EQ(power->grid, chl->grid);
    for (float c : {0.03f, 0.1f, 1.f, 5.f}) {
        const double published = 0.2 * (0.00635 + 0.06 * std::pow(c, 0.65));
        for (float l : {440.f, 540.f}) {
            const double ay = constant->concentration * constant->sigmaA(l) +
                              power->sigmaA(l) * std::pow(c, power->sigmaAExponent(l));
            EXPECT_NEAR(ay, published * std::exp(-0.014 * (l - 440.f)), 1e-3 * published)
                << c << " mg/m³ at " << l << " nm";
        }
        EXPECT_NEAR(case1CdomAbsorption440(c), published, 1e-3 * published);
    }
    // Printed in the docs: 0.0025 1/m at 0.03 mg/m³, 0.0133 at 1, 0.035 at 5.
    EXPECT_NEAR(case1CdomAbsorption440(0.03f), 0.0025, 5e-5);
    EXPECT_NEAR(case1CdomAbsorption440(1.f), 0.0133, 5e-5);
    EXPECT_NEAR(case1CdomAbsorption440(5.f), 0.0354, 5e-5);
}
