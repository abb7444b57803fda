// The tools built on the renderer, subcommands of `mirage`: procedural assets (make-asset), the
// slab instrument (slab), the speed-accuracy sweep (tradeoff) and single light paths (raypath).
// Each registers its options on the command line (add...Command) and runs from its option struct.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/command.h"

namespace mirage {

struct AssetOptions {
    std::string kind, output;
    int resolution = 64;
    double voxels = 0;  // --voxels: a target active voxel count instead of a resolution
    uint64_t seed = 1;
    bool quiet = false;
};
int runMakeAsset(const AssetOptions& o);
Command addMakeAssetCommand(CLI::App& app);

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
Command addSlabCommand(CLI::App& app);

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
Command addTradeoffCommand(CLI::App& app);

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
Command addRaypathCommand(CLI::App& app);

}  // namespace mirage
