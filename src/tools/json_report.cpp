#include "tools/json_report.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "core/text.h"

namespace mirage {

namespace {

std::string inlineJson(const JsonReport& v);

// "key": value, the key escaped by the library.
std::string member(const std::string& key, const JsonReport& value) {
    return JsonReport(key).dump() + ": " + inlineJson(value);
}

std::string inlineJson(const JsonReport& v) {
    if (v.is_object())
        return "{" + joinList(v.items(), [](const auto& kv) { return member(kv.key(), kv.value()); }) +
               "}";
    if (v.is_array())
        return "[" + joinList(v, [](const JsonReport& e) { return inlineJson(e); }) + "]";
    return v.dump();
}

}  // namespace

std::string formatJsonReport(const JsonReport& report) {
    return "{\n  " +
           joinList(report.items(), [](const auto& kv) { return member(kv.key(), kv.value()); },
                    ",\n  ") +
           "\n}\n";
}

JsonReport jsonNumber(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    const double rounded = std::strtod(buf, nullptr);
    if (!std::isfinite(rounded)) return nullptr;
    // 2^53: every whole double below it is an exact int64.
    if (rounded == std::floor(rounded) && std::fabs(rounded) < 0x1p53) return int64_t(rounded);
    return rounded;
}

}  // namespace mirage
