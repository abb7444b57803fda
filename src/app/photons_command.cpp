// `mirage photons SCENE --frame N -o N.photons`: the photon pass of a frame alone, saved for
// the regions of that frame to render from (`mirage render --photons-file`). The command runs
// the render command's frame loop (loading, --set, --seed, --quality, --shutter, $F patterns,
// --skip-existing) with photonsOnly, so a photon file is made from exactly the scene a render
// of the same options would load.
#include <CLI/CLI.hpp>
#include <memory>

#include "app/cli_table.h"
#include "app/commands.h"

namespace mirage {

namespace {

// The options of `mirage render` that decide the photon pass, bound and checked as there, with
// help of their own, in the order of --help; the photon file (-o) is required.
std::vector<CliOption> photonRows(RenderOptions* o) {
    std::vector<CliOption> rows = selectOptions(
        renderOptionRows(o),
        {{"input", "Scene .toml, or a .vdb/.nvdb"},
         {"-o,--output",
          "The photon file; $F4, $F or #### take the frame (a sequence without a "
          "pattern gets .#### before the extension)"},
         {"--frame", "Frame number (default 1)"},
         {"--frames", "Frames A to B (inclusive), e.g. 1-24"},
         {"--set",
          "Override scene values before loading, as for mirage render (the render "
          "must be given the same)"},
         {"--seed", "Random seed (default: film.seed); the render must match"},
         {"--integrator", "An integrator with a photon pass (photon); default: the scene's"},
         {"--quality", "draft, preview or final: the preset's photon count"},
         {"--shutter",
          "Motion blur shutter WIDTH in frames, as for mirage render (photons sample "
          "times in it)"},
         {"--motion-blur", "A 180° shutter (--shutter 0.5)"},
         {"--threads", "Worker threads (default: all cores)"},
         {"--skip-existing", "Skip frames whose photon file is already intact (size and checksum)"},
         {"-q,--quiet", "No progress output"}});
    rows[1].add = required(rows[1].add);
    return rows;
}

}  // namespace

Command addPhotonsCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    o->request.photonsOnly = true;
    auto* cmd = app.add_subcommand(
        "photons",
        "Trace a frame's photon pass alone and save it (-o N.photons) for `mirage render "
        "--photons-file`: every region of the frame then reads the same photons");
    addOptions(*cmd, photonRows(o.get()));
    return {cmd, [o] { return runRender(*o); }};
}

}  // namespace mirage
