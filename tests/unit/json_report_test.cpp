// Tests for the tools' --json output (tools/json_report.h): what the JSON library escapes stays
// valid JSON end to end, numbers keep the digits the report states, and the layout keeps one
// key per line.

#include "tools/json_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "test_support.h"

namespace mirage {
namespace {

TEST(JsonReport, OneKeyPerLineValuesInline) {
    JsonReport j;
    j["name"] = "slab";
    j["values"] = {1, 2.5};
    j["nested"] = {{"a", 1}, {"b", false}};
    EXPECT_EQ(formatJsonReport(j),
              "{\n  \"name\": \"slab\",\n  \"values\": [1, 2.5],\n"
              "  \"nested\": {\"a\": 1, \"b\": false}\n}\n");
}

TEST(JsonReport, QuotesAndBackslashesInStringsStayValidJson) {
    const std::string awkward = "say \"hi\" \\ then\ttab";
    JsonReport j;
    j[awkward] = awkward;
    j["list"] = {awkward};
    const JsonReport back = nlohmann::ordered_json::parse(formatJsonReport(j));
    EXPECT_EQ(back[awkward], awkward);
    EXPECT_EQ(back["list"][0], awkward);
}

TEST(JsonReport, NumbersAsPrintfGWritesThem) {
    EXPECT_EQ(jsonNumber(1.0, 9).dump(), "1");
    EXPECT_TRUE(jsonNumber(1.0, 9).is_number_integer());
    EXPECT_EQ(jsonNumber(0.1234567891234, 9).dump(), "0.123456789");
    EXPECT_EQ(jsonNumber(2.5e-7, 6).dump(), "2.5e-07");
    EXPECT_EQ(jsonNumber(0.1, 17).get<double>(), 0.1);  // 17 digits: the double itself
    EXPECT_TRUE(jsonNumber(std::numeric_limits<double>::quiet_NaN(), 9).is_null());
}

// End to end: a shader whose name has a quote in it, through `mirage slab --json`.
TEST(JsonReport, SlabReportOfAShaderNamedWithAQuoteParses) {
    const std::string dir = test::tempDir(), shader = dir + "/quoted.toml";
    std::ofstream(shader) << "name = 'fog \"quoted\" \\ one'\n"
                             "[[component]]\nname = \"droplets\"\nsigma_a = 0.1\nsigma_s = 0.9\n";
    std::string out;
    ASSERT_EQ(test::runMirage("slab -q --json --shader '" + shader +
                                  "' --thickness 1 --photons 2000 --seed 1",
                              &out),
              0)
        << out;
    nlohmann::ordered_json j;
    ASSERT_NO_THROW(j = nlohmann::ordered_json::parse(out)) << out;
    EXPECT_EQ(j["shader"], "fog \"quoted\" \\ one");
    const double r = j["reflectance"], t = j["transmittance"], a = j["absorbed"];
    EXPECT_NEAR(r + t + a + double(j["capped"]), 1.0, 1e-9) << out;
}

}  // namespace
}  // namespace mirage
