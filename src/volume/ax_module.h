// The seam to Mirage's OpenVDB AX module, libmirage_ax.so (src/modules/ax_module.cpp), which
// grid_expression.cpp loads the first time a scene has a grid expression.
//
// Why a module. libopenvdb_ax brings LLVM 14 with it: linked into the command, it cost every
// start of Mirage about 0.1 s of the dynamic loader's relocations (2 cores, AMD EPYC: a bare
// program linked against the command's other libraries starts in 0.42 s, with AX in 0.51 s),
// whether or not the scene used an expression; most scenes do not. Loaded on demand, only
// scenes with expressions pay it.
//
// The interface passes only standard-library types and, for the grids, an openvdb::GridPtrVec
// behind a void*: both sides link the same libopenvdb and libstdc++. The module throws nothing
// across the seam and knows nothing of Mirage's messages; grid_expression.cpp words them.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mirage {

// What AX made of an expression: Ok, or where it failed and with which messages.
struct AxOutcome {
    enum class Kind { Ok, ParseThrew, SyntaxErrors, CompileThrew, CompileErrors, RunThrew };
    Kind kind = Kind::Ok;
    std::string what;                 // the exception's message (…Threw)
    std::vector<std::string> errors;  // AX's logged errors, "message line:column" (…Errors)
};

// The attribute tokens ("float@density") an expression reads only, writes only, or both.
struct AxTokens {
    std::vector<std::string> readOnly, writeOnly, readWrite;
};

struct AxModule {
    int abi;  // kAxModuleAbi of the module's build: a stale module is refused
    // Parses `code` and catalogues its attribute tokens.
    AxOutcome (*catalogue)(const std::string& code, AxTokens* tokens);
    // A token's name and type ("float@density" → "density", "float").
    void (*nameType)(const std::string& token, std::string* name, std::string* type);
    // Parses, compiles and runs `code` over the grids (an openvdb::GridPtrVec*), AX names bound
    // to grid names by `bindings`, creating no missing grid.
    AxOutcome (*run)(const std::string& code,
                     const std::vector<std::pair<std::string, std::string>>& bindings,
                     void* grids);
};

constexpr int kAxModuleAbi = 1;
constexpr const char* kAxModuleFile = "libmirage_ax.so";
constexpr const char* kAxModuleEntry = "mirage_ax_module";

}  // namespace mirage
