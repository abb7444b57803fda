// `mirage slab --shader … --spectral`: the water-column instrument. A grey shader slab gives
// flat spectra equal to the grey slab's scalar answer; in the ocean slab, photons that are not
// re-emitted walk identically whatever Γ (the Γ roulette ends them either way), so switching
// chlorophyll fluorescence on can only add light, and only inside its band (the 685 nm bump
// of sun-induced chlorophyll fluorescence).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

std::string runSlab(const std::string& args) {
    std::string out;
    int code = mirage::test::runMirage("slab --json -q " + args, &out);
    EXPECT_EQ(code, 0) << out;
    return out;
}

std::vector<double> array(const std::string& json, const std::string& key) {
    std::vector<double> v;
    size_t at = json.find("\"" + key + "\": [");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no array " << key << " in\n" << json;
        return v;
    }
    const char* p = json.c_str() + json.find('[', at) + 1;
    while (*p && *p != ']') {
        char* end;
        v.push_back(std::strtod(p, &end));
        p = end;
        while (*p == ',' || *p == ' ') ++p;
    }
    return v;
}

// The value of a scalar key, which must occur exactly once: a JSON parser keeps only the last
// of repeated keys, so a duplicate would hide either the spectrum or the total from users.
double value(const std::string& json, const std::string& key) {
    const std::string quoted = "\"" + key + "\": ";
    size_t at = json.find(quoted);
    if (at == std::string::npos) {
        ADD_FAILURE() << "no " << key << " in\n" << json;
        return NAN;
    }
    EXPECT_EQ(json.find(quoted, at + 1), std::string::npos) << key << " twice in\n" << json;
    return std::strtod(json.c_str() + at + quoted.size(), nullptr);
}

// A value of the nested `fluorescence` object.
double fluorescence(const std::string& json, const std::string& key) {
    size_t open = json.find("\"fluorescence\": {");
    size_t close = json.find('}', open);
    size_t at = json.find("\"" + key + "\": ", open);
    if (open == std::string::npos || at == std::string::npos || at > close) {
        ADD_FAILURE() << "no fluorescence." << key << " in\n" << json;
        return NAN;
    }
    return std::strtod(json.c_str() + at + key.size() + 4, nullptr);
}

// A top-level row (its own line, two spaces in), as opposed to a nested key of that name.
double row(const std::string& json, const std::string& key) {
    size_t at = json.find("\n  \"" + key + "\": ");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no row " << key << " in\n" << json;
        return NAN;
    }
    return std::strtod(json.c_str() + at + key.size() + 7, nullptr);
}

// Every key of the slab's JSON occurs once.
void expectUniqueKeys(const std::string& json) {
    for (const char* key : {"reflectance", "transmittance", "reflectance_total",
                            "transmittance_total", "wavelength_nm", "fluorescence"}) {
        const std::string quoted = std::string("\"") + key + "\": ";
        size_t at = json.find(quoted);
        ASSERT_NE(at, std::string::npos) << key << " missing in\n" << json;
        EXPECT_EQ(json.find(quoted, at + 1), std::string::npos) << key << " twice in\n" << json;
    }
}

}  // namespace

TEST(SlabSpectral, GreyShaderSlabIsFlatAndMatchesTheGreySlab) {
    std::string dir = mirage::test::tempDir();
    std::ofstream(dir + "/grey.toml") << "[[component]]\nname = \"grey\"\nsigma_a = 0.5\n"
                                         "sigma_s = 0.5\ng = 0.9\n";
    // τ = 1 over 1 m, albedo 0.5, g = 0.9: UR1 = 0.00585, UT1 = 0.59232 (Prahl).
    std::string json =
        runSlab("--shader '" + dir + "/grey.toml' --thickness 1 --spectral --photons 400000");
    auto lambda = array(json, "wavelength_nm"), r = array(json, "reflectance"),
         t = array(json, "transmittance");
    ASSERT_EQ(lambda.size(), 80u);
    ASSERT_EQ(r.size(), 80u);
    EXPECT_DOUBLE_EQ(lambda.front(), 382.5);
    EXPECT_DOUBLE_EQ(lambda.back(), 777.5);
    double meanT = 0;
    for (double x : t) meanT += x / 80;
    EXPECT_NEAR(meanT, 0.59232, 0.005);
    expectUniqueKeys(json);
    EXPECT_NEAR(value(json, "transmittance_total"), 0.59232, 0.005);
    EXPECT_NEAR(value(json, "reflectance_total"), 0.00585, 0.001);
    // Flat: every bin within 5 binomial σ of the mean (5000 photons a bin).
    for (size_t b = 0; b < t.size(); ++b)
        EXPECT_NEAR(t[b], meanT, 5 * std::sqrt(meanT * (1 - meanT) / 5000)) << lambda[b] << " nm";
    EXPECT_EQ(fluorescence(json, "reemitted"), 0.0);
    // Without fluorescence every absorption event ends a photon: the events per photon are the
    // absorbed fraction, which closes the energy balance R + T + A = 1 (no photon capped).
    EXPECT_EQ(row(json, "capped"), 0.0);
    EXPECT_NEAR(fluorescence(json, "absorbed"), row(json, "absorbed"), 1e-9);
    EXPECT_NEAR(row(json, "absorbed") + value(json, "reflectance_total") +
                    value(json, "transmittance_total"),
                1.0, 1e-6);
}

TEST(SlabSpectral, ChlorophyllFluorescenceAddsLightOnlyInItsBand) {
    // The CDOM's own fluorescence (a blue band) off: only chlorophyll's is measured.
    const std::string base = "--shader ocean --set chlorophyll=5 --spectral --photons 300000 "
                             "--n 1.34 --set cdom.quantum_efficiency=0 "
                             "--set chlorophyll.quantum_efficiency=";
    std::string on = runSlab(base + "0.05"), off = runSlab(base + "0");
    auto lambda = array(on, "wavelength_nm"), rOn = array(on, "reflectance"),
         rOff = array(off, "reflectance");
    ASSERT_EQ(rOn.size(), 80u);
    ASSERT_EQ(rOff.size(), 80u);
    double band = 0;
    for (size_t b = 0; b < rOn.size(); ++b) {
        EXPECT_GE(rOn[b], rOff[b] - 1e-9) << lambda[b] << " nm";
        if (lambda[b] < 600) {
            EXPECT_NEAR(rOn[b], rOff[b], 1e-9) << lambda[b] << " nm";
        }
        if (lambda[b] > 670 && lambda[b] < 700) band += rOn[b] - rOff[b];
    }
    EXPECT_GT(band, 0.005);
    EXPECT_GT(fluorescence(on, "reemitted"), 0.0);
    EXPECT_EQ(fluorescence(off, "reemitted"), 0.0);
    // Each absorption event either re-emits (Γ roulette) or ends its photon, so events minus
    // re-emissions counts the photons that ended absorbed. The `absorbed` row is their power,
    // which is less where a re-emission left λi/λo of it: it lies between that count less
    // the re-emissions and the count itself. Re-emissions are a few per cent of the events
    // (Γ = 0.05 of chlorophyll's share of σa).
    const double events = fluorescence(on, "absorbed"), reemitted = fluorescence(on, "reemitted");
    EXPECT_LE(row(on, "absorbed"), events - reemitted + 1e-9);
    EXPECT_GE(row(on, "absorbed"), events - 2 * reemitted - 1e-9);
    EXPECT_LT(reemitted, 0.05 * events);
    // Stokes: the light comes out redder than it went in.
    EXPECT_GT(fluorescence(on, "mean_shift_nm"), 0.0);
}

TEST(SlabSpectral, BadOptionsExitNonZero) {
    std::string out;
    EXPECT_NE(mirage::test::runMirage("slab --set chlorophyll=1", &out), 0);
    EXPECT_NE(mirage::test::runMirage("slab --shader ocean --set plankton=1 -q", &out), 0);
    EXPECT_NE(out.find("water, chlorophyll, cdom"), std::string::npos) << out;
    EXPECT_NE(mirage::test::runMirage("slab --shader ocean --set chlorophyll=-1 -q", &out), 0);
    EXPECT_NE(mirage::test::runMirage("slab --tau 1", &out), 0);
}
