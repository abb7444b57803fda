// The mirage command's own subcommands (render, info, photons, assemble, farm); the tools built
// on the renderer (make-asset, slab, tradeoff, raypath) are in tools/tools.h. main.cpp registers
// every subcommand on one command line (CLI11) and catches MirageError once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "app/cli_table.h"
#include "frame/frame_request.h"
#include "tools/command.h"

namespace mirage {

// `mirage render` and `mirage photons`: the frame request every frame of the command shares
// (frame/frame_request.h), and what the command does with a sequence of frames.
struct RenderOptions {
    FrameRequest request;    // the settings of every frame; its frame is set per frame
    int frame = -1;          // --frame; < 0 = 1
    std::string frames;      // --frames A-B
    int threads = 0;         // --threads; 0 = all cores
    bool resume = false;     // --resume: continue from <out>.partial
    std::string maxMemory;   // --max-memory SIZE (4G, 512M); "" = no budget
    std::string ocioConfig;  // --ocio
};
int runRender(const RenderOptions& o);
Command addRenderCommand(CLI::App& app);
// The options of `mirage render` bound to `o` (render_options.cpp), in the order of its --help.
std::vector<CliOption> renderOptionRows(RenderOptions* o);

// `mirage photons SCENE --frame N -o N.photons`: runRender with photonsOnly (photons_command.cpp).
Command addPhotonsCommand(CLI::App& app);

// `mirage assemble TILE.exr… -o FRAME.exr` (assemble_command.cpp).
Command addAssembleCommand(CLI::App& app);

// `mirage farm SCENE --frames A-B …`: Slurm batch scripts, submitted (farm_command.cpp).
Command addFarmCommand(CLI::App& app);

struct InfoOptions {
    std::string input;
    std::vector<std::string> overrides;
    std::string ocioConfig;
    int frame = 1;            // for $F4 patterns and keyed motion, as `render --frame`
    double shutter = -1;      // --shutter WIDTH (frames); −1: the scene's
    bool motionBlur = false;  // --motion-blur: --shutter 0.5
    bool load = false;        // --load: a bare volume file loaded as a scene, not just listed
};
int runInfo(const InfoOptions& o);
Command addInfoCommand(CLI::App& app);

}  // namespace mirage
