// Grid expressions: which grids an expression reads and writes, and running it, through
// Mirage's OpenVDB AX module (volume/ax_module.h), loaded the first time a scene has one. This
// file words every message; the module only reports what AX said.
#include "volume/grid_expression.h"

#include <algorithm>

#include "core/clock.h"
#include "core/module.h"
#include "volume/ax_module.h"

namespace mirage {

namespace {

const AxModule& ax() {
    static const AxModule* module = [] {
        auto entry = reinterpret_cast<const AxModule* (*)()>(
            moduleEntry(kAxModuleFile, kAxModuleEntry, "grid expressions (OpenVDB AX)"));
        const AxModule* m = entry();
        if (!m || m->abi != kAxModuleAbi)
            throw MirageError(std::string(kAxModuleFile) +
                              " is from another build of Mirage; rebuild it with the command");
        return m;
    }();
    return *module;
}

// AX's logged errors, bounded: a long snippet can produce dozens.
std::string errorText(const std::vector<std::string>& errors) {
    std::string s;
    for (size_t i = 0; i < errors.size() && i < 3; ++i) s += (i ? "; " : "") + errors[i];
    if (errors.size() > 3) s += "; and " + std::to_string(errors.size() - 3) + " more";
    if (s.empty()) s = "unknown error";
    return boundedMessage(s) + " (line:column within the expression)";
}

[[noreturn]] void fail(const GridExpression& e, const std::string& message) {
    throw MirageError(e.where, e.label + ": " + message);
}

// Throws the message of a failed outcome; `file` names the grids' file for a failed run.
void check(const GridExpression& e, const AxOutcome& o, const std::string& file = "") {
    using Kind = AxOutcome::Kind;
    switch (o.kind) {
    case Kind::Ok:
        return;
    case Kind::ParseThrew:
        fail(e, "OpenVDB AX could not parse the expression: " + boundedMessage(o.what));
    case Kind::SyntaxErrors:
        fail(e, "OpenVDB AX syntax error: " + errorText(o.errors));
    case Kind::CompileThrew:
        fail(e, "OpenVDB AX could not compile the expression: " + boundedMessage(o.what));
    case Kind::CompileErrors:
        fail(e, "OpenVDB AX could not compile the expression: " + errorText(o.errors));
    case Kind::RunThrew:
        fail(e, "OpenVDB AX failed on " + file + ": " + boundedMessage(o.what));
    }
}

std::string gridName(const GridExpression& e, const std::string& axName) {
    for (const auto& [name, grid] : e.bindings)
        if (name == axName) return grid;
    return axName;
}

void addOnce(std::vector<std::string>* names, const std::string& n) {
    if (std::find(names->begin(), names->end(), n) == names->end()) names->push_back(n);
}

}  // namespace

ExpressionAccess expressionAccess(const GridExpression& e) {
    AxTokens tokens;
    check(e, ax().catalogue(e.code, &tokens));
    ExpressionAccess access;
    auto add = [&](const std::vector<std::string>& list, bool reads, bool writes) {
        for (const std::string& token : list) {
            std::string name, type;
            ax().nameType(token, &name, &type);
            if (type != "float")
                fail(e, "grid '" + name + "' is accessed as " + type +
                            "; Mirage's grids are scalar float fog volumes (write @" + name +
                            " or f@" + name + ")");
            if (reads) addOnce(&access.reads, gridName(e, name));
            if (writes) addOnce(&access.writes, gridName(e, name));
        }
    };
    add(tokens.readOnly, true, false);
    add(tokens.writeOnly, false, true);
    add(tokens.readWrite, true, true);
    if (access.writes.empty())
        fail(e, "the expression writes no grid (expected an assignment such as "
                "@density = …;)");
    return access;
}

std::string describeAccess(const ExpressionAccess& access) {
    auto list = [](const std::vector<std::string>& names) {
        std::string s;
        for (const auto& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
        return s.empty() ? std::string("nothing") : s;
    };
    return "reads " + list(access.reads) + "; writes " + list(access.writes);
}

double runGridExpressionOn(const GridExpression& e, void* grids, const std::string& file) {
    const Clock::time_point start = Clock::now();
    check(e, ax().run(e.code, e.bindings, grids), file);
    return secondsSince(start);
}

}  // namespace mirage
