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
    std::string quality;           // --quality draft|preview|final; "" = the scene's settings
    bool resume = false;           // --resume: continue from <out>.partial
    bool skipExisting = false;     // --skip-existing: skip frames whose EXR is complete
    std::string maxMemory;         // --max-memory SIZE (4G, 512M); "" = no budget
    double shutter = -1;           // --shutter WIDTH in frames, centred; < 0 = the scene's
    bool motionBlur = false;       // --motion-blur: --shutter 0.5
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

// `mirage slab`: photons through a plane-parallel slab (slab_command.cpp documents it).
struct SlabOptions {
    double albedo = -1, tau = 0, g = 0;  // single-scattering albedo, optical thickness, HG g
                                         // (the defaults mean "not given": needed without
                                         // --shader)
    std::string shader;                  // --shader: name or .toml; replaces albedo/tau/g
    std::vector<std::string> sets;       // --set NAME=C (component concentration) …
    double thickness = 0;                // --thickness, m; 0 = a deep (optically infinite) column
    bool spectral = false;               // --spectral: flat 380–780 nm source, 5 nm bins
    double n = 1, nOutside = 1;         // refractive index of the slab and of its surroundings
    std::string incidence = "normal";   // normal (collimated) | diffuse (Lambertian)
    uint64_t photons = 1000000, seed = 0;
    int64_t maxEvents = 1000000;  // per photon: scatterings + internal reflections
    int threads = 0;
    bool json = false, quiet = false;
};
int runSlab(const SlabOptions& o);

// `mirage tradeoff`: error against a reference versus render time over a sweep of scene
// settings (tradeoff_command.cpp documents it).
struct TradeoffOptions {
    std::string input;                   // scene .toml
    std::string reference;               // --reference EXR; "" = render one with volpath
    int referenceSpp = 0;                // 0: max(256, 4 × the sweep's highest spp)
    std::vector<std::string> vary;       // NAME=v1,v2,… (Cartesian product over the options)
    std::vector<std::string> overrides;  // --set, applied before the varied keys
    std::string resolution;              // WxH
    std::string integrator;              // "" = the scene's (or a varied render.integrator)
    int spp = 0, threads = 0, repeats = 1;
    int64_t seed = -1;
    std::string prefix;                  // -o: output files are <prefix>tradeoff.csv, …
    std::string ocioConfig;
    bool quiet = false;
};
int runTradeoff(const TradeoffOptions& o);

}  // namespace mirage

namespace mirage {

// `mirage raypath`: one light path through a refractive-index profile by the renderer's path
// stepper (raypath_command.cpp documents it).
struct RaypathOptions {
    std::string profile = "linear";      // linear | atmosphere
    double n0 = 1.0, k = 0.0;            // linear: n = n0 + k·y
    std::string origin = "0,0,0", direction = "1,0,0";  // x,y,z (m; any length)
    double length = 1.0;                 // arc length, m
    double tolerance = 1e-6;             // RK45 error tolerance per step
    std::string method = "rk45";         // rk45 | euler
    double step = 1e-2;                  // euler: fixed step, m
    double maxStep = 0;                  // rk45: largest step, m (0 = unlimited)
    double wavelength = 550;             // nm
    int64_t maxSteps = 10'000'000;
    std::vector<std::string> inversions; // atmosphere: base,top,dT[,blend] (m, m, K, m)
    bool json = false;
};
int runRaypath(const RaypathOptions& o);

}  // namespace mirage
