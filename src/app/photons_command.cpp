// `mirage photons SCENE --frame N -o N.photons`: the photon pass of a frame alone, saved for
// the regions of that frame to render from (`mirage render --photons-file`). The command runs
// the render command's frame loop (loading, --set, --seed, --quality, --shutter, $F patterns,
// --skip-existing) with photonsOnly, so a photon file is made from exactly the scene a render
// of the same options would load.
#include <CLI/CLI.hpp>
#include <memory>

#include "app/commands.h"

namespace mirage {

Command addPhotonsCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    o->request.photonsOnly = true;
    auto* cmd = app.add_subcommand(
        "photons",
        "Trace a frame's photon pass alone and save it (-o N.photons) for `mirage render "
        "--photons-file`: every region of the frame then reads the same photons");
    cmd->add_option("input", o->request.input, "Scene .toml, or a .vdb/.nvdb")->required();
    cmd->add_option("-o,--output", o->request.output,
                    "The photon file; $F4, $F or #### take the frame (a sequence without a "
                    "pattern gets .#### before the extension)")
        ->required();
    cmd->add_option("--frame", o->frame, "Frame number (default 1)");
    cmd->add_option("--frames", o->frames, "Frames A to B (inclusive), e.g. 1-24")
        ->excludes("--frame");
    cmd->add_option("--set", o->request.overrides,
                    "Override scene values before loading, as for mirage render (the render "
                    "must be given the same)")
        ->take_all();
    cmd->add_option("--seed", o->request.seed,
                    "Random seed (default: film.seed); the render must match")
        ->check(CLI::Range(int64_t(0), INT64_MAX));
    cmd->add_option("--integrator", o->request.integrator,
                    "An integrator with a photon pass (photon); default: the scene's");
    cmd->add_option("--quality", o->request.quality,
                    "draft, preview or final: the preset's photon count")
        ->check(CLI::IsMember({"draft", "preview", "final"}));
    cmd->add_option("--shutter", o->request.shutter,
                    "Motion blur shutter WIDTH in frames, as for mirage render (photons sample "
                    "times in it)")
        ->check(CLI::Range(0.0, 2.0));
    cmd->add_flag("--motion-blur", o->request.motionBlur, "A 180° shutter (--shutter 0.5)")
        ->excludes("--shutter");
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    cmd->add_flag("--skip-existing", o->request.skipExisting,
                  "Skip frames whose photon file is already intact (size and checksum)");
    cmd->add_flag("-q,--quiet", o->request.quiet, "No progress output");
    return {cmd, [o] { return runRender(*o); }};
}

}  // namespace mirage
