// One frame to render, as a plain request: everything `mirage render` sets on a frame. The
// command line fills it (app/render_options.cpp); a program builds it in code (the Python
// module, a host application's render button). loadFrame (frame_load.h) loads the scene and
// applies the request to it once; renderFrame (render_frame.h) renders it and writeFrame
// (frame_output.h) writes what the command writes. Every field but `input` is optional: its
// default keeps what the scene file says.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mirage {

struct FrameRequest {
    // The scene.
    std::string input;                   // scene .toml, or a bare .vdb/.nvdb
    int frame = 1;                       // $F patterns, keyed motion, the turntable's position
    std::vector<std::string> overrides;  // --set key.path=value, before the scene is parsed
    // The scene's TOML when a program holds it in memory (the Python module's Scene.from_dict):
    // `input` then only names it, in messages, and its folder resolves the scene's relative
    // paths. "" = read `input`.
    std::string sceneText;

    // The render.
    std::string integrator;         // --integrator single|volpath|photon|auto; "" = the scene's
    std::string quality;            // --quality draft|preview|final; "" = the scene's settings
    std::string resolution;         // --resolution WxH; "" = film.resolution
    int spp = 0;                    // --spp; 0 = film.spp (or --quality's)
    int64_t seed = -1;              // --seed; < 0 = film.seed
    int passes = 0;                 // --passes N: a render in passes, at most N; 0 = none
    double timeLimit = 0;           // --time-limit SECONDS; 0 = none
    double noiseThreshold = 0;      // --noise-threshold E; 0 = none
    int coarseSpp = 0;              // --coarse SPP: the coarse image alone; 0 = none
    std::string region;             // --region X0,Y0,X1,Y1; "" = the whole frame
    int turntable = 0;              // --turntable N: `frame` is frame 1..N of the orbit; 0 = none
    std::vector<std::string> aovs;  // --aov: passes after [output] aovs
    double shutter = -1;            // --shutter WIDTH in frames, centred; < 0 = the scene's
    bool motionBlur = false;        // --motion-blur: --shutter 0.5
    std::string photonsFile;        // --photons-file: a saved photon pass ($F patterns expand)
    uint64_t memoryBudget = 0;      // --max-memory, bytes; 0 = none

    // The output.
    std::string output;         // -o; "" = the scene's [output] path
    std::string preview;        // --preview; "" = the scene's, if any
    std::string deep;           // --deep; "" = the scene's [output] deep, if any
    bool floatExr = false;      // --float: 32-bit float instead of the scene's [output] half
    bool sequence = false;      // one frame of several: outputs without a pattern are numbered
    bool skipExisting = false;  // --skip-existing: nothing to do when the output is complete
    bool photonsOnly = false;   // `mirage photons`: the output is the frame's photon file
    bool quiet = false;         // -q: no progress and no summary on stderr
};

// Throws MirageError for a request the command line refuses before it runs (CLI11's checks in
// app/render_options.cpp): a value out of its range, or two options that exclude each other.
void checkFrameRequest(const FrameRequest& request);

// An output path of frame `frame`: a $F4, $F or #### pattern expanded, else, in a sequence, the
// frame number before the extension (out.exr → out.0007.exr).
std::string framePath(const std::string& path, int frame, bool sequence);

}  // namespace mirage
