// The mirage command's subcommands. main.cpp parses the command line (CLI11) into these option
// structs and catches MirageError once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mirage {

struct RenderOptions {
    std::string input;             // scene .toml or a bare .vdb/.nvdb
    std::string output;            // -o; "" = the scene's [output] path
    std::string preview;           // --preview; "" = the scene's, if any
    int frame = -1;                // --frame
    std::string frames;            // --frames A-B
    std::vector<std::string> overrides;  // --set
    std::string resolution;        // --resolution WxH
    int spp = 0, threads = 0, turntable = 0;
    int64_t seed = -1;
    bool quiet = false, floatExr = false;
    std::string ocioConfig;
    std::string integrator;        // --integrator; "" = the scene's
};
int runRender(const RenderOptions& o);

struct InfoOptions {
    std::string input;
    std::vector<std::string> overrides;
    std::string ocioConfig;
};
int runInfo(const InfoOptions& o);

struct AssetOptions {
    std::string kind, output;
    int resolution = 64;
    uint64_t seed = 1;
};
int runMakeAsset(const AssetOptions& o);

}  // namespace mirage
