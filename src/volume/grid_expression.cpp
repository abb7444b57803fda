// Grid expressions with OpenVDB AX: parsing (which grids an expression reads and writes),
// compiling and running. The only translation unit that includes AX headers; they need no LLVM
// headers (the compiler keeps LLVM behind forward declarations), only libopenvdb_ax.so.
//
// Measured on the 2-core CI machine: parsing, compiling (LLVM JIT) and running a one-line remap
// or combine on a 32³ cache costs 0.03–0.05 s idle, up to 0.3 s with the cores busy; once per
// volume and frame. Running it is a parallel pass over the active voxels.
#include "volume/grid_expression.h"

#include <openvdb_ax/Exceptions.h>
#include <openvdb_ax/ast/Scanners.h>
#include <openvdb_ax/compiler/Compiler.h>
#include <openvdb_ax/compiler/Logger.h>
#include <openvdb_ax/compiler/VolumeExecutable.h>

#include <algorithm>
#include <mutex>

#include "core/clock.h"
#include "volume/openvdb_expression.h"

namespace mirage {

namespace {

void initAx() {
    // ax::initialize() starts LLVM's JIT (and OpenVDB); documented as thread-safe, but once is
    // all it needs.
    static std::once_flag once;
    std::call_once(once, [] { openvdb::ax::initialize(); });
}

// Collects AX's errors (one line each, "message line:column") instead of printing them.
struct ErrorLog {
    std::vector<std::string> errors;
    openvdb::ax::Logger logger;

    ErrorLog()
        : logger([this](const std::string& m) { errors.push_back(m); },
                 [](const std::string&) {}) {
        logger.setNumberedOutput(false);
        logger.setErrorPrefix("");
        logger.setPrintLines(false);
    }

    // The first few errors, bounded: a long snippet can produce dozens.
    std::string text() const {
        std::string s;
        for (size_t i = 0; i < errors.size() && i < 3; ++i) s += (i ? "; " : "") + errors[i];
        if (errors.size() > 3) s += "; and " + std::to_string(errors.size() - 3) + " more";
        if (s.empty()) s = "unknown error";
        return boundedMessage(s) + " (line:column within the expression)";
    }
};

[[noreturn]] void fail(const GridExpression& e, const std::string& message) {
    throw MirageError(e.where, e.label + ": " + message);
}

openvdb::ax::ast::Tree::ConstPtr parse(const GridExpression& e) {
    initAx();
    ErrorLog log;
    openvdb::ax::ast::Tree::ConstPtr tree;
    try {
        tree = openvdb::ax::ast::parse(e.code.c_str(), log.logger);
    } catch (const std::exception& ex) {
        fail(e, "OpenVDB AX could not parse the expression: " + boundedMessage(ex.what()));
    }
    if (!tree || log.logger.hasError())
        fail(e, "OpenVDB AX syntax error: " + log.text());
    return tree;
}

std::string gridName(const GridExpression& e, const std::string& axName) {
    for (const auto& [ax, grid] : e.bindings)
        if (ax == axName) return grid;
    return axName;
}

void addOnce(std::vector<std::string>* names, const std::string& n) {
    if (std::find(names->begin(), names->end(), n) == names->end()) names->push_back(n);
}

}  // namespace

ExpressionAccess expressionAccess(const GridExpression& e) {
    const openvdb::ax::ast::Tree::ConstPtr tree = parse(e);
    std::vector<std::string> readOnly, writeOnly, readWrite;
    openvdb::ax::ast::catalogueAttributeTokens(*tree, &readOnly, &writeOnly, &readWrite);
    ExpressionAccess access;
    auto add = [&](const std::vector<std::string>& tokens, bool reads, bool writes) {
        for (const std::string& token : tokens) {
            std::string name, type;
            openvdb::ax::ast::Attribute::nametypeFromToken(token, &name, &type);
            if (type != "float")
                fail(e, "grid '" + name + "' is accessed as " + type +
                            "; Mirage's grids are scalar float fog volumes (write @" + name +
                            " or f@" + name + ")");
            if (reads) addOnce(&access.reads, gridName(e, name));
            if (writes) addOnce(&access.writes, gridName(e, name));
        }
    };
    add(readOnly, true, false);
    add(writeOnly, false, true);
    add(readWrite, true, true);
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

double runGridExpression(const GridExpression& e, openvdb::GridPtrVec& grids,
                         const std::string& file) {
    const Clock::time_point start = Clock::now();
    const openvdb::ax::ast::Tree::ConstPtr tree = parse(e);
    ErrorLog log;
    openvdb::ax::VolumeExecutable::Ptr exe;
    try {
        exe = openvdb::ax::Compiler::create()->compile<openvdb::ax::VolumeExecutable>(*tree,
                                                                                     log.logger);
    } catch (const std::exception& ex) {
        fail(e, "OpenVDB AX could not compile the expression: " + boundedMessage(ex.what()));
    }
    if (!exe || log.logger.hasError())
        fail(e, "OpenVDB AX could not compile the expression: " + log.text());
    openvdb::ax::AttributeBindings bindings;
    for (const auto& [ax, grid] : e.bindings) bindings.set(ax, grid);
    exe->setAttributeBindings(bindings);
    // A grid the file lacks is an error (the loader checks first, naming the file's grids);
    // a created grid would be empty, since AX writes only where a grid is active.
    exe->setCreateMissing(false);
    try {
        exe->execute(grids);
    } catch (const std::exception& ex) {
        fail(e, "OpenVDB AX failed on " + file + ": " + boundedMessage(ex.what()));
    }
    return secondsSince(start);
}

}  // namespace mirage
