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

// The options, in the order of --help: those of `mirage render` that decide the photon pass.
std::vector<CliOption> photonRows(RenderOptions* o) {
    FrameRequest& r = o->request;
    return {
        {"input", "Scene .toml, or a .vdb/.nvdb", required(value(&r.input))},
        {"-o,--output",
         "The photon file; $F4, $F or #### take the frame (a sequence without a "
         "pattern gets .#### before the extension)",
         required(value(&r.output))},
        {"--frame", "Frame number (default 1)", value(&o->frame)},
        {"--frames", "Frames A to B (inclusive), e.g. 1-24", value(&o->frames), {"--frame"}},
        {"--set",
         "Override scene values before loading, as for mirage render (the render "
         "must be given the same)",
         allValues(&r.overrides)},
        {"--seed", "Random seed (default: film.seed); the render must match",
         value(&r.seed, CLI::Range(int64_t(0), INT64_MAX))},
        {"--integrator", "An integrator with a photon pass (photon); default: the scene's",
         value(&r.integrator)},
        {"--quality", "draft, preview or final: the preset's photon count",
         value(&r.quality, CLI::IsMember({"draft", "preview", "final"}))},
        {"--shutter",
         "Motion blur shutter WIDTH in frames, as for mirage render (photons sample "
         "times in it)",
         value(&r.shutter, CLI::Range(0.0, 2.0))},
        {"--motion-blur", "A 180° shutter (--shutter 0.5)", flag(&r.motionBlur), {"--shutter"}},
        {"--threads", "Worker threads (default: all cores)",
         value(&o->threads, CLI::Range(1, 4096))},
        {"--skip-existing", "Skip frames whose photon file is already intact (size and checksum)",
         flag(&r.skipExisting)},
        {"-q,--quiet", "No progress output", flag(&r.quiet)},
    };
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
