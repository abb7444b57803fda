// The --json results of the tools: an nlohmann ordered_json object (keys in insertion order)
// printed with one top-level key per line and arrays and nested objects inline, so that a
// person can read it and a script can grep a key, while every string is escaped by the JSON
// library (a shader named `a "b"` stays valid JSON).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace mirage {

using JsonReport = nlohmann::ordered_json;

// "{\n  \"key\": value,\n  ...\n}\n"; values inline, ", " and ": " between their parts.
std::string formatJsonReport(const JsonReport& report);

// `v` as a report states it: rounded to `digits` significant decimal digits (the library then
// prints the shortest text of that value), and a JSON integer when the rounded value is whole,
// as printf's %g writes it (1, not 1.0). NaN and infinities become null.
JsonReport jsonNumber(double v, int digits);

}  // namespace mirage
