// Tests for film/color and film/film: Mirage's OCIO config (ociocheck, published matrices,
// agreement with ocioconvert), the ColorPipeline's errors, and the film's accumulation.

#include "film/color.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/error.h"
#include "core/rng.h"
#include "film/film.h"
#include "film/image_io.h"
#include "spectrum/cie.h"
#include "test_support.h"

namespace mirage {
namespace {

// The pipeline on the built-in config, whatever $OCIO the test runner has.
ColorPipeline builtin(const std::string& workingSpace = "") {
    ::unsetenv("OCIO");
    return ColorPipeline("", workingSpace);
}

std::string writeBuiltinConfig(const std::string& dir) {
    std::string path = dir + "/config.ocio";
    std::ofstream(path) << builtinOcioConfig();
    return path;
}

bool haveTool(const char* path) { return ::access(path, X_OK) == 0; }

// --- The config --------------------------------------------------------------------------------

TEST(ColorConfigTest, BuiltinConfigIsTheAssetFile) {
    std::string asset = test::sourceDir() + "/assets/ocio/config.ocio";
    std::ifstream in(asset);
    if (!in) GTEST_SKIP() << asset << " is absent; skipping";
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), builtinOcioConfig()) << "rebuild: the embedded config is stale";
}

TEST(ColorConfigTest, PassesOciocheck) {
    if (!haveTool("/usr/bin/ociocheck")) GTEST_SKIP() << "/usr/bin/ociocheck is absent; skipping";
    std::string path = writeBuiltinConfig(test::tempDir());
    std::string output;
    int rc = test::runCommand("/usr/bin/ociocheck --iconfig '" + path + "'", &output);
    EXPECT_EQ(rc, 0) << output;
    EXPECT_NE(output.find("passed"), std::string::npos) << output;
    EXPECT_EQ(output.find("ERROR"), std::string::npos) << output;
    EXPECT_EQ(output.find("WARNING"), std::string::npos) << output;
}

TEST(ColorConfigTest, ColourSpacesDisplaysAndViews) {
    ColorPipeline color = builtin();
    EXPECT_EQ(color.workingSpace(), "ACEScg");
    EXPECT_EQ(color.configDescription(), "built-in");
    std::vector<std::string> spaces = color.colorSpaces();
    for (const char* name : {"ACES2065-1", "ACEScg", "ACEScct", "Linear Rec.709 (sRGB)",
                             "CIE XYZ D65", "sRGB", "Rec.1886 Rec.709", "Raw"})
        EXPECT_NE(std::find(spaces.begin(), spaces.end(), name), spaces.end()) << name;
    EXPECT_EQ(color.displays(), (std::vector<std::string>{"sRGB", "Rec.709"}));
    EXPECT_EQ(color.views("sRGB"), (std::vector<std::string>{"Standard", "Raw"}));
    EXPECT_EQ(color.views("Rec.709"), (std::vector<std::string>{"Standard", "Raw"}));
    EXPECT_TRUE(color.views("no such display").empty());
}

// D65 white XYZ (0.95047, 1, 1.08883) is adapted to the ACES white by Bradford: ACEScg (1,1,1).
TEST(ColorConfigTest, D65WhiteIsAcescgWhite) {
    ColorPipeline color = builtin();
    Vec3d rgb = color.xyzToWorking().apply(Vec3d(0.95047, 1.0, 1.08883));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb[c], 1.0, 1e-3) << c;
    Mat3 id = color.xyzToWorking() * color.workingToXyz();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(id(r, c), r == c ? 1.0 : 0.0, 1e-12);
}

// The commonly published Rec.709 → ACEScg matrix (Bradford), first column.
TEST(ColorConfigTest, Rec709RedInAcescg) {
    ColorPipeline color = builtin("Linear Rec.709 (sRGB)");
    std::vector<float> px = {1.f, 0.f, 0.f};
    color.convert(px, 3, "ACEScg");
    EXPECT_NEAR(px[0], 0.6131f, 1e-4f);
    EXPECT_NEAR(px[1], 0.0702f, 1e-4f);
    EXPECT_NEAR(px[2], 0.0206f, 1e-4f);
}

TEST(ColorConfigTest, AcesWorkingSpacesCarryTheirPublishedChromaticities) {
    const std::vector<float> ap1 = {0.713f, 0.293f, 0.165f,   0.830f,
                                    0.128f, 0.044f, 0.32168f, 0.33767f};
    const std::vector<float> ap0 = {0.7347f, 0.2653f,  0.0f,     1.0f,
                                    0.0001f, -0.0770f, 0.32168f, 0.33767f};
    std::vector<float> cg = builtin().workingChromaticities();
    std::vector<float> aces = builtin("ACES2065-1").workingChromaticities();
    ASSERT_EQ(cg.size(), 8u);
    ASSERT_EQ(aces.size(), 8u);
    for (int i = 0; i < 8; ++i) {
        EXPECT_NEAR(cg[i], ap1[i], 1e-5f) << i;
        EXPECT_NEAR(aces[i], ap0[i], 1e-5f) << i;
    }
}

TEST(ColorConfigTest, SrgbDisplayEncodesMiddleGrey) {
    ColorPipeline color = builtin();
    // Grey stays grey (white maps to white); sRGB encodes 0.18 as 1.055·0.18^(1/2.4) − 0.055.
    std::vector<float> px = {0.18f, 0.18f, 0.18f, 0.5f};
    color.toDisplay(px, 4, "sRGB", "Standard");
    float expect = 1.055f * std::pow(0.18f, 1.f / 2.4f) - 0.055f;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(px[c], expect, 1e-5f);
    EXPECT_EQ(px[3], 0.5f);  // alpha untouched
    // ACEScct of 0.18 (Academy S-2016-001): (log2(0.18) + 9.72) / 17.52.
    std::vector<float> cct = {0.18f, 0.18f, 0.18f};
    color.convert(cct, 3, "ACEScct");
    EXPECT_NEAR(cct[0], (std::log2(0.18f) + 9.72f) / 17.52f, 1e-5f);
}

// --- Errors ------------------------------------------------------------------------------------

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

TEST(ColorPipelineTest, ErrorsNameTheCulpritAndTheValidNames) {
    std::string e = errorOf([] { ColorPipeline("/nonexistent/config.ocio"); });
    EXPECT_NE(e.find("/nonexistent/config.ocio"), std::string::npos) << e;

    e = errorOf([] { builtin("ACEScgg"); });
    EXPECT_NE(e.find("'ACEScgg'"), std::string::npos) << e;
    EXPECT_NE(e.find("'ACEScg'"), std::string::npos) << e;

    e = errorOf([] { builtin("ACEScct"); });  // a log space cannot hold the film's sums
    EXPECT_NE(e.find("not linear"), std::string::npos) << e;

    ColorPipeline color = builtin();
    std::vector<float> px = {0.5f, 0.5f, 0.5f};
    e = errorOf([&] { color.convert(px, 3, "Nope"); });
    EXPECT_NE(e.find("'Nope'"), std::string::npos) << e;
    EXPECT_NE(e.find("'Linear Rec.709 (sRGB)'"), std::string::npos) << e;
    e = errorOf([&] { color.toDisplay(px, 3, "DCI", "Standard"); });
    EXPECT_NE(e.find("'DCI'"), std::string::npos) << e;
    EXPECT_NE(e.find("'Rec.709'"), std::string::npos) << e;
    e = errorOf([&] { color.toDisplay(px, 3, "sRGB", "Filmic"); });
    EXPECT_NE(e.find("'Filmic'"), std::string::npos) << e;
    EXPECT_NE(e.find("'Standard'"), std::string::npos) << e;
}

TEST(ColorPipelineTest, OcioEnvironmentVariableAndExplicitPath) {
    std::string path = writeBuiltinConfig(test::tempDir());
    ::setenv("OCIO", path.c_str(), 1);
    ColorPipeline fromEnv;
    EXPECT_EQ(fromEnv.configDescription(), path);
    ::setenv("OCIO", "/nonexistent/from_env.ocio", 1);
    std::string e = errorOf([] { ColorPipeline(); });
    EXPECT_NE(e.find("/nonexistent/from_env.ocio"), std::string::npos) << e;
    EXPECT_NE(e.find("$OCIO"), std::string::npos) << e;
    ColorPipeline explicitPath(path);  // an explicit path wins over $OCIO
    EXPECT_EQ(explicitPath.configDescription(), path);
    ::unsetenv("OCIO");

    std::string bad = test::tempDir() + "/bad.ocio";
    std::ofstream(bad) << "ocio_profile_version: 2\ncolorspaces: [oops\n";
    e = errorOf([&] { ColorPipeline{bad}; });
    EXPECT_NE(e.find(bad), std::string::npos) << e;
}

// --- Agreement with ocioconvert ----------------------------------------------------------------

// Runs ocioconvert on a float EXR written by Mirage and compares with ColorPipeline on the same
// pixels: the same config text, two independent callers of OCIO.
void compareWithOcioconvert(const std::string& ocioArgs,
                            const std::function<void(std::vector<float>&)>& mirageConvert) {
    std::string dir = test::tempDir();
    std::string config = writeBuiltinConfig(dir);
    Image in;
    in.width = 3;
    in.height = 2;
    in.rgba = {0.18f, 0.18f, 0.18f, 1.f, 1.f,   0.f,  0.f,   1.f, 0.02f, 0.5f, 2.5f, 0.5f,
               0.9f,  0.7f,  0.1f,  1.f, -0.1f, 0.3f, 0.05f, 1.f, 8.f,   4.f,  1.f,  1.f};
    ExrOptions opt;
    opt.halfFloat = false;
    writeExr(dir + "/in.exr", in, opt);
    std::string cmd =
        "cd '" + dir + "' && OCIO='" + config + "' " + OCIOCONVERT_BINARY + " " + ocioArgs;
    std::string output;
    ASSERT_EQ(test::runCommand(cmd, &output), 0) << cmd << "\n" << output;
    Image out = readExr(dir + "/out.exr");
    std::vector<float> mine = in.rgba;
    mirageConvert(mine);
    ASSERT_EQ(out.rgba.size(), mine.size());
    double maxDiff = 0.0;
    for (size_t i = 0; i < mine.size(); ++i) {
        maxDiff = std::max(maxDiff, double(std::abs(out.rgba[i] - mine[i])));
        EXPECT_NEAR(out.rgba[i], mine[i], 1e-4f) << "value " << i;
    }
    std::cout << "[ measured ] max |ocioconvert − Mirage| = " << maxDiff << "\n";
}

TEST(ColorOcioconvertTest, AcescgToLinearRec709) {
    if (!haveTool(OCIOCONVERT_BINARY)) GTEST_SKIP() << OCIOCONVERT_BINARY << " is absent";
    ColorPipeline color = builtin();
    compareWithOcioconvert(
        "in.exr ACEScg out.exr 'Linear Rec.709 (sRGB)'",
        [&](std::vector<float>& px) { color.convert(px, 4, "Linear Rec.709 (sRGB)"); });
}

TEST(ColorOcioconvertTest, AcescgToSrgbDisplay) {
    if (!haveTool(OCIOCONVERT_BINARY)) GTEST_SKIP() << OCIOCONVERT_BINARY << " is absent";
    ColorPipeline color = builtin();
    compareWithOcioconvert(
        "--view in.exr ACEScg out.exr sRGB Standard",
        [&](std::vector<float>& px) { color.toDisplay(px, 4, "sRGB", "Standard"); });
}

TEST(ColorOcioconvertTest, AcescgToRec709Display) {
    if (!haveTool(OCIOCONVERT_BINARY)) GTEST_SKIP() << OCIOCONVERT_BINARY << " is absent";
    ColorPipeline color = builtin();
    compareWithOcioconvert("in.exr ACEScg out.exr 'Rec.1886 Rec.709'", [&](std::vector<float>& px) {
        color.convert(px, 4, "Rec.1886 Rec.709");
    });
}

// --- Film --------------------------------------------------------------------------------------

// A deterministic stream of samples over a small film.
void feed(Film& film, bool withBadSamples) {
    for (int s = 0; s < 64; ++s) {
        for (int y = 0; y < film.height(); ++y) {
            for (int x = 0; x < film.width(); ++x) {
                Sampler rng(11, uint64_t(y * film.width() + x), uint64_t(s));
                SampledWavelengths w = SampledWavelengths::sampleVisible(rng.get1D());
                SampledSpectrum L;
                for (int i = 0; i < kSpectrumSamples; ++i) L[i] = 10.f * rng.get1D();
                float alpha = rng.get1D() < 0.8f ? 1.f : 0.f;
                film.addSample(x, y, L, w, alpha);
                if (withBadSamples && x == 1 && y == 2 && s % 16 == 0) {
                    SampledSpectrum bad = L;
                    bad[s / 16 % kSpectrumSamples] = s % 32 ? std::nanf("") : kInfinity;
                    film.addSample(x, y, bad, w, alpha);
                    film.addSample(x, y, L, w, std::nanf(""));
                }
            }
        }
    }
}

TEST(FilmTest, IdenticalSampleSequencesGiveIdenticalBits) {
    ColorPipeline color = builtin();
    Film a(5, 4), b(5, 4);
    feed(a, false);
    feed(b, false);
    Image ia = a.develop(color), ib = b.develop(color);
    ASSERT_EQ(ia.rgba.size(), ib.rgba.size());
    EXPECT_EQ(std::memcmp(ia.rgba.data(), ib.rgba.data(), ia.rgba.size() * sizeof(float)), 0);
    EXPECT_EQ(a.nonFiniteSamples(), 0u);
}

TEST(FilmTest, NonFiniteSamplesAreCountedAndDropped) {
    ColorPipeline color = builtin();
    Film clean(5, 4), dirty(5, 4);
    feed(clean, false);
    feed(dirty, true);
    EXPECT_EQ(dirty.nonFiniteSamples(), 8u);  // 4 bad spectra + 4 bad alphas at pixel (1, 2)
    Image ic = clean.develop(color), id = dirty.develop(color);
    EXPECT_EQ(std::memcmp(ic.rgba.data(), id.rgba.data(), ic.rgba.size() * sizeof(float)), 0);
    for (float v : id.rgba) EXPECT_TRUE(std::isfinite(v));
}

TEST(FilmTest, DevelopAveragesXyzIntoTheWorkingSpace) {
    ColorPipeline color = builtin();
    Film film(2, 1);
    SampledWavelengths w = SampledWavelengths::sampleVisible(0.25f);
    SampledSpectrum L(2.f);
    film.addSample(0, 0, L, w, 1.f);
    film.addSample(0, 0, L * 3.f, w, 0.f);
    Image img = film.develop(color);
    Vec3d expect = color.xyzToWorking().apply(Vec3d(spectrumToXyz(L * 2.f, w)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.pixel(0, 0)[c], expect[c], 1e-5 * expect[c]);
    EXPECT_FLOAT_EQ(img.pixel(0, 0)[3], 0.5f);
    for (int c = 0; c < 4; ++c) EXPECT_EQ(img.pixel(1, 0)[c], 0.f);  // no samples: empty
}

}  // namespace
}  // namespace mirage
