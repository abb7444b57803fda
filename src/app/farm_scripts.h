// The Slurm batch scripts of a shot (`mirage farm`): plain text, made from the shot's plan
// alone, so that --dry-run prints exactly what a submission hands to sbatch.
//
// Three kinds of job array, each task one `mirage` command (Slurm array index = frame):
//  - photons: one task per frame, `mirage photons` → photons/<frame>.photons (only for an
//    integrator with a photon pass);
//  - render, one array per tile: `mirage render --region` of that tile → tiles/<frame>.t<i>.exr,
//    --resume (a requeued task continues its partial file) and --photons-file; each array is
//    submitted with --dependency=aftercorr:<photons>, so frame f's tile waits for frame f's
//    photons only;
//  - assemble: `mirage assemble` of the frame's tiles → frames/<stem>.<frame>.exr, aftercorr on
//    every render array.
// Every array is --requeue (a task of a lost node runs again) with one log per task in logs/,
// named by kind, frame and tile, appended to across requeues.
#pragma once

#include <string>
#include <vector>

#include "frame/frame_regions.h"

namespace mirage {

struct FarmPlan {
    std::string mirage;       // absolute path of the mirage binary
    std::string scene;        // absolute path of the scene
    std::string dir;          // absolute folder of the shot's files
    std::string stem;         // the frames' file name stem
    std::vector<int> frames;  // to submit
    TileGrid tiles;
    std::vector<PixelWindow> regions;         // tiles.count() regions of the frame
    bool photons = false;                     // the integrator traces photons: a photon array
    std::vector<std::string> sharedArgs;      // to photons and render alike (--set, --seed, …)
    std::vector<std::string> renderOnlyArgs;  // to render alone (--resolution, --spp)
    std::string partition, timeLimit;         // "" = the cluster's default
    int cpus = 0;                             // --cpus-per-task; 0 = the cluster's default
    bool skipExisting = false;                // tasks skip outputs that are already complete
};

struct FarmScript {
    std::string name;  // file name in <dir>/scripts
    std::string text;
    // The script's dependencies, by index of earlier scripts in the list (aftercorr).
    std::vector<int> after;
};

// The scripts in submission order: photons (if any), render per tile, assemble.
std::vector<FarmScript> farmScripts(const FarmPlan& plan);

// Slurm's --array list of the frames: "1-3,7,9-12".
std::string arraySpec(const std::vector<int>& frames);

// The path of a frame's output, photons file or tile (as the scripts name them), for frame f.
std::string farmFramePath(const FarmPlan& plan, int frame);
std::string farmTilePath(const FarmPlan& plan, int frame, int tile);

// A word quoted for the POSIX shell.
std::string shellQuote(const std::string& word);

}  // namespace mirage
