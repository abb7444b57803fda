// `mirage assemble TILE.exr… -o FRAME.exr`: the regions of a frame rendered apart (`mirage
// render --region`, a farm's tiles) joined into the frame, every channel and layer they carry
// (film/exr_assembly.h checks that they are one frame and cover it exactly once).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_table.h"
#include "app/commands.h"
#include "core/text.h"
#include "film/exr_assembly.h"
#include "film/exr_header.h"

namespace mirage {

namespace {

struct AssembleOptions {
    std::vector<std::string> tiles;
    std::string output;
    bool skipExisting = false;
    bool quiet = false;
};

int runAssemble(const AssembleOptions& o) {
    if (o.skipExisting && isCompleteFrame(o.output)) {
        if (!o.quiet) std::fprintf(stderr, "%s is complete, skipped\n", o.output.c_str());
        return 0;
    }
    const AssemblyReport r = assembleRegions(o.tiles, o.output);
    if (!o.quiet)
        std::fprintf(stderr,
                     "assembled %zu regions into a %dx%d frame: %d subimage(s), channels %s\n",
                     o.tiles.size(), r.width, r.height, r.subimages, joinList(r.channels).c_str());
    std::printf("%s\n", o.output.c_str());
    return 0;
}

}  // namespace

Command addAssembleCommand(CLI::App& app) {
    auto o = std::make_shared<AssembleOptions>();
    auto* cmd = app.add_subcommand(
        "assemble",
        "Join regions of a frame (mirage render --region) into the frame: every channel and "
        "layer, checked to come from one frame and cover it exactly once; written atomically");
    addOptions(*cmd, {{"regions", "The regions' EXR files", required(value(&o->tiles))},
                      {"-o,--output", "The frame's EXR", required(value(&o->output))},
                      {"--skip-existing",
                       "Do nothing when the output is already complete (mirage:complete = true)",
                       flag(&o->skipExisting)},
                      {"-q,--quiet", "No summary", flag(&o->quiet)}});
    return {cmd, [o] { return runAssemble(*o); }};
}

}  // namespace mirage
