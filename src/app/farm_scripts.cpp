#include "app/farm_scripts.h"

#include <cctype>
#include <cstdio>

namespace mirage {

namespace {

// A number zero-padded to `digits` (frames 0007, tiles 02), as the file names carry them.
std::string padded(int n, int digits) {
    char b[32];
    std::snprintf(b, sizeof b, "%0*d", digits, n);
    return b;
}

// The #SBATCH lines every array shares. %4a: the array index (the frame), zero-padded.
std::string header(const FarmPlan& p, const std::string& job, const std::string& log) {
    std::string h = "#!/bin/bash\n";
    // #SBATCH lines are not read by a shell: the name keeps only characters that need no quotes.
    std::string name = "mirage-" + job + "-" + p.stem;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
            c = '_';
    h += "#SBATCH --job-name=" + name + "\n";
    h += "#SBATCH --array=" + arraySpec(p.frames) + "\n";
    h += "#SBATCH --requeue\n";
    h += "#SBATCH --open-mode=append\n";
    h += "#SBATCH --output=" + p.dir + "/logs/" + log + ".log\n";
    if (!p.partition.empty()) h += "#SBATCH --partition=" + p.partition + "\n";
    if (!p.timeLimit.empty()) h += "#SBATCH --time=" + p.timeLimit + "\n";
    if (p.cpus > 0) h += "#SBATCH --cpus-per-task=" + std::to_string(p.cpus) + "\n";
    h += "set -euo pipefail\n";
    h += "F=$SLURM_ARRAY_TASK_ID\n";
    h += "F4=$(printf %04d \"$F\")\n";
    h += "echo \"== $(date -u +%FT%TZ) $(hostname) job ${SLURM_ARRAY_JOB_ID}_${F} "
         "restart ${SLURM_RESTART_COUNT:-0}\"\n";
    return h;
}

// The command line's tail: threads, the pass-through options, --skip-existing.
std::string commonArgs(const FarmPlan& p, bool render) {
    std::string a;
    if (p.cpus > 0) a += " --threads " + std::to_string(p.cpus);
    for (const std::string& arg : p.sharedArgs) a += " " + shellQuote(arg);
    if (render)
        for (const std::string& arg : p.renderOnlyArgs) a += " " + shellQuote(arg);
    if (p.skipExisting) a += " --skip-existing";
    return a;
}

std::string photonsPathInScript(const FarmPlan& p) { return p.dir + "/photons/\"$F4\".photons"; }

}  // namespace

std::string shellQuote(const std::string& word) {
    std::string q = "'";
    for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string arraySpec(const std::vector<int>& frames) {
    std::string spec;
    for (size_t i = 0; i < frames.size();) {
        size_t j = i;
        while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
        if (!spec.empty()) spec += ",";
        spec += std::to_string(frames[i]);
        if (j > i) spec += "-" + std::to_string(frames[j]);
        i = j + 1;
    }
    return spec;
}

std::string farmFramePath(const FarmPlan& p, int frame) {
    return p.dir + "/frames/" + p.stem + "." + padded(frame, 4) + ".exr";
}

std::string farmTilePath(const FarmPlan& p, int frame, int tile) {
    return p.dir + "/tiles/" + padded(frame, 4) + ".t" + padded(tile, 2) + ".exr";
}

std::vector<FarmScript> farmScripts(const FarmPlan& p) {
    std::vector<FarmScript> scripts;
    const std::string mirage = shellQuote(p.mirage), scene = shellQuote(p.scene);
    if (p.photons) {
        FarmScript s{"photons.sh", header(p, "photons", "photons.f%4a"), {}};
        s.text += "exec " + mirage + " photons " + scene + " --frame \"$F\" -o " +
                  photonsPathInScript(p) + " -q" + commonArgs(p, false) + "\n";
        scripts.push_back(s);
    }
    std::vector<int> renders;
    for (int t = 0; t < p.tiles.count(); ++t) {
        const std::string tile = "t" + padded(t, 2);
        FarmScript s{
            "render." + tile + ".sh", header(p, "render-" + tile, "render.f%4a." + tile), {}};
        if (p.photons) s.after.push_back(0);
        s.text += "exec " + mirage + " render " + scene + " --frame \"$F\" --region " +
                  formatPixelWindow(p.regions[size_t(t)]) + " -o " + p.dir + "/tiles/\"$F4\"." +
                  tile + ".exr --resume -q" +
                  (p.photons ? " --photons-file " + photonsPathInScript(p) : std::string()) +
                  commonArgs(p, true) + "\n";
        renders.push_back(int(scripts.size()));
        scripts.push_back(s);
    }
    FarmScript a{"assemble.sh", header(p, "assemble", "assemble.f%4a"), renders};
    a.text += "exec " + mirage + " assemble";
    for (int t = 0; t < p.tiles.count(); ++t)
        a.text += " " + p.dir + "/tiles/\"$F4\".t" + padded(t, 2) + ".exr";
    a.text += " -o " + p.dir + "/frames/" + shellQuote(p.stem) + ".\"$F4\".exr -q" +
              (p.skipExisting ? " --skip-existing" : "") + "\n";
    scripts.push_back(a);
    return scripts;
}

}  // namespace mirage
