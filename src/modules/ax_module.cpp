// Mirage's OpenVDB AX module (volume/ax_module.h): the one translation unit with AX headers,
// built as libmirage_ax.so and loaded when a scene first has a grid expression. AX's headers
// keep LLVM behind forward declarations: only libopenvdb_ax.so is linked.
//
// Measured on the 2-core CI machine: parsing, compiling (LLVM JIT) and running a one-line remap
// or combine on a 32³ cache costs 0.03–0.05 s idle, up to 0.3 s with the cores busy; once per
// volume and frame. Running it is a parallel pass over the active voxels.
#include <openvdb_ax/Exceptions.h>
#include <openvdb_ax/ast/Scanners.h>
#include <openvdb_ax/compiler/Compiler.h>
#include <openvdb_ax/compiler/Logger.h>
#include <openvdb_ax/compiler/VolumeExecutable.h>

#include <mutex>

#include "volume/ax_module.h"

namespace {

using mirage::AxOutcome;

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
};

AxOutcome failed(AxOutcome::Kind kind, std::string what, std::vector<std::string> errors = {}) {
    AxOutcome o;
    o.kind = kind;
    o.what = std::move(what);
    o.errors = std::move(errors);
    return o;
}

AxOutcome parse(const std::string& code, openvdb::ax::ast::Tree::ConstPtr* tree) {
    initAx();
    ErrorLog log;
    try {
        *tree = openvdb::ax::ast::parse(code.c_str(), log.logger);
    } catch (const std::exception& ex) {
        return failed(AxOutcome::Kind::ParseThrew, ex.what());
    }
    if (!*tree || log.logger.hasError())
        return failed(AxOutcome::Kind::SyntaxErrors, "", log.errors);
    return {};
}

AxOutcome catalogue(const std::string& code, mirage::AxTokens* tokens) {
    openvdb::ax::ast::Tree::ConstPtr tree;
    AxOutcome o = parse(code, &tree);
    if (o.kind != AxOutcome::Kind::Ok) return o;
    openvdb::ax::ast::catalogueAttributeTokens(*tree, &tokens->readOnly, &tokens->writeOnly,
                                               &tokens->readWrite);
    return o;
}

void nameType(const std::string& token, std::string* name, std::string* type) {
    openvdb::ax::ast::Attribute::nametypeFromToken(token, name, type);
}

AxOutcome run(const std::string& code,
              const std::vector<std::pair<std::string, std::string>>& names, void* grids) {
    openvdb::ax::ast::Tree::ConstPtr tree;
    AxOutcome o = parse(code, &tree);
    if (o.kind != AxOutcome::Kind::Ok) return o;
    ErrorLog log;
    openvdb::ax::VolumeExecutable::Ptr exe;
    try {
        exe = openvdb::ax::Compiler::create()->compile<openvdb::ax::VolumeExecutable>(*tree,
                                                                                     log.logger);
    } catch (const std::exception& ex) {
        return failed(AxOutcome::Kind::CompileThrew, ex.what());
    }
    if (!exe || log.logger.hasError())
        return failed(AxOutcome::Kind::CompileErrors, "", log.errors);
    openvdb::ax::AttributeBindings bindings;
    for (const auto& [ax, grid] : names) bindings.set(ax, grid);
    exe->setAttributeBindings(bindings);
    // A grid the file lacks is an error (the loader checks first, naming the file's grids);
    // a created grid would be empty, since AX writes only where a grid is active.
    exe->setCreateMissing(false);
    try {
        exe->execute(*static_cast<openvdb::GridPtrVec*>(grids));
    } catch (const std::exception& ex) {
        return failed(AxOutcome::Kind::RunThrew, ex.what());
    }
    return o;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const mirage::AxModule* mirage_ax_module() {
    static const mirage::AxModule module{mirage::kAxModuleAbi, catalogue, nameType, run};
    return &module;
}
