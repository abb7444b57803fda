// The mirage command's own subcommands (render, info, photons, assemble, farm); the tools built
// on the renderer (make-asset, slab, tradeoff, raypath) are in tools/tools.h. main.cpp registers
// every subcommand on one command line (CLI11) and catches MirageError once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/command.h"

namespace mirage {

struct RenderOptions {
    std::string input;             // scene .toml or a bare .vdb/.nvdb
    std::string output;            // -o; "" = the scene's [output] path
    std::string preview;           // --preview; "" = the scene's, if any
    int frame = -1;                // --frame
    std::string frames;            // --frames A-B
    std::vector<std::string> overrides;  // --set
    std::vector<std::string> aovs;       // --aov, after [output] aovs
    std::string deep;                    // --deep; "" = the scene's [output] deep, if any
    std::string resolution;        // --resolution WxH
    int spp = 0, threads = 0, turntable = 0;
    int64_t seed = -1;
    bool quiet = false, floatExr = false;
    std::string ocioConfig;
    std::string integrator;        // --integrator; "" = the scene's
    std::string quality;           // --quality draft|preview|final; "" = the scene's settings
    bool resume = false;           // --resume: continue from <out>.partial
    bool skipExisting = false;     // --skip-existing: skip frames whose EXR is complete
    std::string maxMemory;         // --max-memory SIZE (4G, 512M); "" = no budget
    double shutter = -1;           // --shutter WIDTH in frames, centred; < 0 = the scene's
    bool motionBlur = false;       // --motion-blur: --shutter 0.5
    int passes = 0;                // --passes N: a render in passes, at most N
    double timeLimit = 0;          // --time-limit SECONDS; 0 = none
    double noiseThreshold = 0;     // --noise-threshold E; 0 = none
    int coarseSpp = 0;             // --coarse SPP: the coarse image alone; 0 = none
    std::string region;            // --region X0,Y0,X1,Y1; "" = the whole frame
    std::string photonsFile;       // --photons-file: a saved photon pass ($F patterns expand)
    bool photonsOnly = false;      // `mirage photons`: the photon pass alone, -o a .photons file
};
int runRender(const RenderOptions& o);
Command addRenderCommand(CLI::App& app);

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
};
int runInfo(const InfoOptions& o);
Command addInfoCommand(CLI::App& app);

}  // namespace mirage
