// IES LM-63 profiles (light/ies_file.h, light/emission_profile.h): the test files of
// tests/ies/ read back at their angles and between them, symmetries folded, the profile's
// solid angle by quadrature, a lamp's radiance ∝ the profile with its power kept, photon
// directions drawn by it (a weighted χ²), and malformed files refused with the file, the line
// and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "chi_square.h"
#include "core/error.h"
#include "light/ies_file.h"
#include "light/lamp.h"
#include "test_support.h"

using namespace mirage;

namespace {

std::string iesFile(const std::string& name) { return test::sourceDir() + "/tests/ies/" + name; }

// The downlight's candela over γ = 0, 15, …, 90 (rotationally symmetric).
const float kDown[] = {1000, 950, 800, 550, 250, 60, 0};

// f(γ) of the downlight, linear between its angles.
double downlight(double gammaDeg) {
    if (gammaDeg >= 90) return 0;
    const int i = int(gammaDeg / 15);
    const double t = gammaDeg / 15 - i;
    return (kDown[i] + t * (kDown[i + 1] - kDown[i])) / 1000.0;
}

const char* kHeader = "IESNA:LM-63-2002\n[TEST] x\nTILT=NONE\n";

// The message of the MirageError parse throws, or "" when it parses.
std::string parseError(const std::string& text) {
    try {
        IesProfile::parse(text, "bad.ies");
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(IesProfile, ReadsTheTestFiles) {
    const IesProfile down = IesProfile::read(iesFile("downlight.ies"));
    EXPECT_EQ(down.verticalCount(), 7);
    EXPECT_EQ(down.horizontalCount(), 1);
    EXPECT_FLOAT_EQ(down.peak(), 1000.f);
    for (int i = 0; i < 7; ++i)
        for (float c : {0.f, 77.f, 300.f}) EXPECT_FLOAT_EQ(down.candela(15.f * i, c), kDown[i]);
    EXPECT_FLOAT_EQ(down.candela(37.5f, 10.f), 0.5f * (800 + 550));
    EXPECT_EQ(down.candela(120.f, 0.f), 0.f);  // above the file's range

    // The headlight: a tilt table, commas, multiplier 2, bilateral symmetry about C 0–180.
    const IesProfile head = IesProfile::read(iesFile("headlight.ies"));
    EXPECT_EQ(head.horizontalCount(), 5);
    EXPECT_FLOAT_EQ(head.peak(), 18000.f);
    EXPECT_FLOAT_EQ(head.candela(0.f, 90.f), 2 * 9000.f);
    EXPECT_FLOAT_EQ(head.candela(10.f, 270.f), 2 * 6000.f);  // mirrors C = 90
    EXPECT_FLOAT_EQ(head.candela(10.f, 22.5f), 2 * 0.5f * (3000 + 4500));
    EXPECT_FLOAT_EQ(head.candela(5.f, 180.f), 2 * 0.5f * (3000 + 2500));
}

TEST(IesProfile, RefusesMalformedFilesNamingTheLine) {
    struct Case {
        std::string text, expected;
    };
    const std::string h = kHeader;
    const std::vector<Case> cases = {
        {"", "bad.ies: expected a 'TILT=' line"},
        {"IESNA:LM-63-2002\nTILT=lamp.tlt\n", "bad.ies:2: expected TILT=NONE or TILT=INCLUDE"},
        {h + "1 1000 1.0 7", "bad.ies:4: expected the number of horizontal angles"},
        {h + "1 1000 x 3 1 1 2 0 0 0\n", "bad.ies:4: expected the candela multiplier"},
        {h + "1 1000 1 3 1 2 2 0 0 0\n1 1 0\n0 45 90\n0\n1 1 1\n",
         "bad.ies:4: expected photometric type 1"},
        {h + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 90 45\n0\n1 1 1\n",
         "bad.ies:6: expected vertical angles increasing"},
        {h + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n1 -1 1\n",
         "bad.ies:8: expected a candela value ≥ 0"},
        {h + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n1 1\n",
         "bad.ies:8: expected a candela value ≥ 0, found the end of the file"},
        {h + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 90\n0\n0 0 0\n",
         "bad.ies:8: expected some candela value above 0"},
        {h + "1 1000 1 3 2 1 2 0 0 0\n1 1 0\n0 45 90\n0 45\n1 1 1 1 1 1\n",
         "bad.ies:7: expected horizontal angles from 0 to 0, 90, 180 or 360"},
        {h + "1 1000 1 99999999 1 1 2 0 0 0\n",
         "bad.ies:4: expected the number of vertical angles"},
        {h + "1 1000 1 3 1 1 2 0 0 0\n1 1 0\n0 45 nan\n", "bad.ies:6: expected vertical angles"},
        {"TILT=INCLUDE\n1\n2\n0 90\n1\n", "bad.ies:5: expected a tilt multiplying factor"},
    };
    for (const Case& c : cases) {
        const std::string message = parseError(c.text);
        EXPECT_EQ(message.rfind(c.expected, 0), 0u) << "got: " << message;
    }
    try {
        IesProfile::read(iesFile("missing.ies"));
        FAIL() << "a missing file was read";
    } catch (const MirageError& e) {
        EXPECT_NE(std::string(e.what()).find("missing.ies"), std::string::npos);
    }
}

TEST(IesProfile, GarbageNeverCrashes) {
    // Random bytes and a valid file cut or mangled at every point: an error or a profile.
    const std::string text =
        kHeader + std::string("1 1000 1 3 2 1 2 0 0 0\n1 1 0\n0 45 90\n") + "0 90\n3 2 1 3 2 1\n";
    Sampler s(4, 0, 0);
    for (size_t cut = 0; cut <= text.size(); ++cut) {
        std::string mangled = text.substr(0, cut);
        if (cut < text.size()) mangled += char(32 + int(s.get1D() * 90));
        mangled += text.substr(std::min(text.size(), cut + 1));
        for (const std::string& t : {text.substr(0, cut), mangled}) {
            try {
                const IesProfile p = IesProfile::parse(t, "fuzz.ies");
                EXPECT_GT(p.peak(), 0.f);
                EXPECT_TRUE(std::isfinite(p.candela(30.f, 45.f)));
            } catch (const MirageError&) {
            }
        }
    }
}

TEST(IesProfile, ProfileKeepsThePowerAndShapesTheIntensity) {
    ProfileDesc desc;
    desc.ies = std::make_shared<const IesProfile>(IesProfile::read(iesFile("downlight.ies")));
    const EmissionProfile profile(desc);
    // Ω_f = 2π ∫ f(γ) sin γ dγ, by a fine midpoint rule.
    double omega = 0.0;
    const int n = 90000;
    for (int i = 0; i < n; ++i) {
        const double g = (i + 0.5) * 90.0 / n;
        omega += downlight(g) * std::sin(g * kPi / 180) * (kPi / 2 / n);
    }
    omega *= 2 * kPi;
    EXPECT_NEAR(profile.solidAngle(), omega, 2e-3 * omega);

    // A lamp 4 m above a point: Li d² = Φ f(γ) / Ω_f, the power shaped, not scaled.
    LampDesc lamp;
    lamp.position = Vec3(0.f, 4.f, 0.f);
    lamp.powerW = 60.f;
    lamp.profile = desc;
    auto light = makeLamp(lamp, Spectrum(1.f));
    const SampledWavelengths w = SampledWavelengths::sampleVisible(0.4f);
    for (float gamma : {0.f, 20.f, 50.f, 80.f}) {
        const Vec3 p =
            lamp.position + Vec3(std::sin(radians(gamma)), -std::cos(radians(gamma)), 0.f) * 4.f;
        LightSample ls;
        const bool lit = light->sampleLi(p, 0.5f, 0.5f, w, &ls);
        const double expected =
            60.0 * downlight(gamma) / profile.solidAngle() / double(kLambdaMax - kLambdaMin);
        EXPECT_NEAR(lit ? ls.Li[0] * 16.0 : 0.0, expected, 1e-4 * expected) << gamma;
    }
    LightSample up;
    EXPECT_FALSE(light->sampleLi(Vec3(0.f, 9.f, 0.f), 0.5f, 0.5f, w, &up));
}

TEST(IesProfile, PhotonsFollowTheProfile) {
    // Weighted χ² over cells in (φ, cos γ): Σ_b (W_b − N P_b)² / Σ_{i∈b} w_i², with P_b the
    // profile's share of cell b by quadrature, for the asymmetric headlight on a sphere lamp
    // aimed along +x; and the weights' mean 1 (all the power, none added).
    LampDesc lamp;
    lamp.position = Vec3(0.f, 0.5f, 0.f);
    lamp.radius = 0.05f;
    lamp.profile.axis = Vec3(1.f, 0.f, 0.f);
    lamp.profile.ies =
        std::make_shared<const IesProfile>(IesProfile::read(iesFile("headlight.ies")));
    const EmissionProfile profile(lamp.profile);
    auto light = makeLamp(lamp, Spectrum(1.f));
    Bounds3 around;
    around.expand(Vec3(-3.f));
    around.expand(Vec3(3.f));
    const int nu = 12, nv = 10, n = 200000;
    const Frame frame(lamp.profile.axis);
    auto cell = [&](const Vec3& d) {
        const Vec3 l = frame.toLocal(d);
        const int u = std::min(nu - 1, int((std::atan2(l.y, l.x) + kPi) / (2 * kPi) * nu));
        const int v = std::min(nv - 1, int(0.5f * (1.f - l.z) * nv));
        return v * nu + u;
    };
    std::vector<double> weight(nu * nv, 0.0), weight2(nu * nv, 0.0), expected(nu * nv, 0.0);
    const int q = 64;  // quadrature points per cell side
    for (int v = 0; v < nv * q; ++v)
        for (int u = 0; u < nu * q; ++u) {
            const float cz = 1.f - 2.f * (v + 0.5f) / (nv * q), sz = std::sqrt(1.f - cz * cz);
            const float phi = -kPi + 2.f * kPi * (u + 0.5f) / (nu * q);
            const Vec3 d = frame.toWorld(Vec3(sz * std::cos(phi), sz * std::sin(phi), cz));
            expected[(v / q) * nu + u / q] +=
                profile.eval(d) * 4 * kPi / (double(nu * q) * nv * q) / profile.solidAngle();
        }
    test::SampleMean mean;
    Sampler s(8, 0, 0);
    for (int i = 0; i < n; ++i) {
        PhotonEmission e;
        const bool ok = light->emitPhoton(around, s, &e);
        const double wgt = ok ? e.weight : 0.0;
        mean.add(wgt);
        if (!ok) continue;
        ASSERT_NEAR(length(e.origin - lamp.position), 0.05f, 1e-5f);
        weight[cell(e.direction)] += wgt;
        weight2[cell(e.direction)] += wgt * wgt;
    }
    EXPECT_NEAR(mean.mean(), 1.0, 4 * mean.standardError() + 2e-3);
    double chi = 0.0;
    int bins = 0;
    for (int b = 0; b < nu * nv; ++b) {
        if (weight2[b] <= 0.0) {
            EXPECT_LT(expected[b], 1e-4) << "cell " << b << " drew nothing";
            continue;
        }
        chi += (weight[b] - n * expected[b]) * (weight[b] - n * expected[b]) / weight2[b];
        ++bins;
    }
    EXPECT_LT(chi, test::chiSquareCritical(bins)) << bins << " cells";
}
