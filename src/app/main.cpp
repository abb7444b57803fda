// mirage — command-line entry point. One try/catch: user mistakes (MirageError) print one
// message and exit 1; command-line syntax errors exit 2 (CLI11's convention).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "tools/tools.h"

namespace {

using mirage::Command;

// Runs the subcommand the command line named; a user mistake is one message and exit code 1.
int runGivenCommand(const std::vector<Command>& commands) {
    try {
        for (const Command& c : commands)
            if (*c.subcommand) return c.run();
    } catch (const mirage::MirageError& e) {
        std::fprintf(stderr, "mirage: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "mirage: error: %s\n", mirage::boundedMessage(e.what()).c_str());
        return 1;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace mirage;
    CLI::App app{"Mirage " MIRAGE_VERSION " — spectral volume renderer for OpenVDB caches"};
    app.require_subcommand(1);
    app.set_version_flag("--version", MIRAGE_VERSION);
    // In this order in --help.
    const std::vector<Command> commands = {
        addRenderCommand(app),   addInfoCommand(app),     addPhotonsCommand(app),
        addAssembleCommand(app), addFarmCommand(app),     addMakeAssetCommand(app),
        addSlabCommand(app),     addTradeoffCommand(app), addRaypathCommand(app)};

    // Command-line syntax errors exit 2 (docs/hostile-input.md, "Input rules"); CLI11's own codes (105 for a
    // bad option value, 106 for a missing one, ...) would tell a farm wrapper nothing stable.
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : 2;
    }
    return runGivenCommand(commands);
}
