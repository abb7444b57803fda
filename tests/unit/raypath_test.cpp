// `mirage raypath`: the JSON it prints matches the exact path in the linear profile, Euler is
// selectable, the atmosphere profile runs, and bad values give one message and exit 1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "medium/linear_profile_path.h"
#include "test_support.h"

namespace mirage {
namespace {

// The numbers after "key": in a flat JSON object (a number or an array of numbers).
std::vector<double> jsonNumbers(const std::string& json, const std::string& key) {
    const size_t at = json.find("\"" + key + "\":");
    if (at == std::string::npos) return {};
    std::vector<double> v;
    const char* p = json.c_str() + at + key.size() + 3;
    while (*p == ' ' || *p == '[') ++p;
    for (;;) {
        char* end = nullptr;
        const double x = std::strtod(p, &end);
        if (end == p) break;
        v.push_back(x);
        p = end;
        while (*p == ' ') ++p;
        if (*p != ',') break;
        ++p;
        while (*p == ' ') ++p;
        if (*p == '"') break;  // the next key: this value was a single number
    }
    return v;
}

TEST(Raypath, LinearProfileJsonMatchesTheExactPath) {
    std::string out;
    ASSERT_EQ(test::runMirage("raypath --profile linear --n0 1.0 --k 0.05 --origin 0,0.5,0 "
                              "--direction 1,0.2,0 --length 10 --tolerance 1e-9 --json",
                              &out),
              0)
        << out;
    const LinearProfilePath ex = exactLinearProfilePath(
        1.0, 0.05, Vec3d(0, 1, 0), Vec3d(0, 0.5, 0), normalize(Vec3d(1, 0.2, 0)), 10.0);
    const std::vector<double> p = jsonNumbers(out, "end_point");
    const std::vector<double> d = jsonNumbers(out, "end_direction");
    ASSERT_EQ(p.size(), 3u) << out;
    ASSERT_EQ(d.size(), 3u) << out;
    EXPECT_LT(length(Vec3d(p[0], p[1], p[2]) - ex.endPoint), 1e-7);
    EXPECT_NEAR(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), 1.0, 1e-12);
    EXPECT_LT(length(Vec3d(d[0], d[1], d[2]) - ex.endDirection), 1e-7);
    const std::vector<double> opl = jsonNumbers(out, "optical_path_length");
    ASSERT_EQ(opl.size(), 1u) << out;
    EXPECT_NEAR(opl[0], ex.opticalPathLength, 1e-7);
    for (const char* key : {"steps", "evaluations", "seconds"})
        EXPECT_EQ(jsonNumbers(out, key).size(), 1u) << key << "\n" << out;
    EXPECT_GT(jsonNumbers(out, "steps")[0], 1);
}

TEST(Raypath, EulerIsLessAccurateThanRk45AtTheSameEvaluations) {
    std::string rk, eu;
    const std::string common =
        "raypath --profile linear --n0 1 --k -0.1 --origin 0,0,0 --direction 1,0.3,0 "
        "--length 5 --json ";
    ASSERT_EQ(test::runMirage(common + "--tolerance 1e-6", &rk), 0) << rk;
    const double evals = jsonNumbers(rk, "evaluations").at(0);
    ASSERT_EQ(test::runMirage(common + "--method euler --step " + std::to_string(5.0 / evals),
                              &eu),
              0)
        << eu;
    EXPECT_NEAR(jsonNumbers(eu, "evaluations").at(0), evals, 2);
    EXPECT_GT(jsonNumbers(eu, "end_point_error").at(0),
              100 * jsonNumbers(rk, "end_point_error").at(0));
}

TEST(Raypath, AtmosphereWithAGroundInversionBendsARayUp) {
    std::string out;
    ASSERT_EQ(test::runMirage("raypath --profile atmosphere --inversion -2,0.5,30,1 "
                              "--origin 0,5,0 --direction 1,-0.0035,0 --length 3000 "
                              "--max-step 5 --json",
                              &out),
              0)
        << out;
    const std::vector<double> p = jsonNumbers(out, "end_point");
    const std::vector<double> d = jsonNumbers(out, "end_direction");
    ASSERT_EQ(p.size(), 3u) << out;
    EXPECT_GT(d.at(1), 0.0) << out;  // heading up again
    EXPECT_GT(p[1], 0.0) << out;
}

TEST(Raypath, BadValuesGiveOneMessage) {
    std::string out;
    EXPECT_EQ(test::runMirage("raypath --origin 1,2 --json", &out), 1);
    EXPECT_NE(out.find("--origin"), std::string::npos) << out;
    EXPECT_EQ(test::runMirage("raypath --direction 0,0,0", &out), 1);
    EXPECT_NE(out.find("--direction"), std::string::npos) << out;
    EXPECT_EQ(test::runMirage("raypath --profile atmosphere --inversion 5,1,30", &out), 1);
    EXPECT_NE(out.find("--inversion"), std::string::npos) << out;
    EXPECT_EQ(test::runMirage("raypath --k 0.1 --length 10 --max-steps 3 --max-step 0.1", &out),
              1);
    EXPECT_NE(out.find("step cap"), std::string::npos) << out;
    EXPECT_EQ(test::runMirage("raypath --method midpoint", &out), 2);
}

}  // namespace
}  // namespace mirage
