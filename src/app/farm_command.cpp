// `mirage farm SCENE --frames A-B [--tiles CxR] …`: a shot on a Slurm farm. The command writes
// the batch scripts of app/farm_scripts.h into <dir>/scripts and submits them with sbatch,
// wiring each array's tasks to the tasks of the same frame in the arrays it depends on
// (--dependency=aftercorr). Nothing in it schedules: Slurm runs, requeues and reports the tasks
// (squeue, sacct); docs/farm.md says how to follow a shot and rerun what failed.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_table.h"
#include "app/commands.h"
#include "app/farm_scripts.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "film/color.h"
#include "film/exr_header.h"
#include "frame/frame_settings.h"
#include "render/integrator.h"
#include "scene/scene.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

struct FarmOptions {
    std::string input, frames, tiles = "1x1", dir, partition, timeLimit;
    std::vector<std::string> overrides;
    std::string resolution, integrator, quality;
    int spp = 0, cpus = 0;
    int64_t seed = -1;
    bool dryRun = false, skipExisting = false;
};

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal(); }

std::string selfPath() {
    std::error_code ec;
    fs::path p = fs::read_symlink("/proc/self/exe", ec);
    if (ec) throw MirageError("mirage farm: cannot find the mirage binary (/proc/self/exe)");
    return p.string();
}

// The options every task passes on to mirage photons and render (the photon pass must see
// the same scene as the render: the same --set, seed and quality).
std::vector<std::string> passThrough(const FarmOptions& o) {
    std::vector<std::string> a;
    for (const std::string& s : o.overrides) a.insert(a.end(), {"--set", s});
    if (o.seed >= 0) a.insert(a.end(), {"--seed", std::to_string(o.seed)});
    if (!o.integrator.empty()) a.insert(a.end(), {"--integrator", o.integrator});
    if (!o.quality.empty()) a.insert(a.end(), {"--quality", o.quality});
    return a;
}

// Render-only options (mirage photons takes neither).
std::vector<std::string> renderOnly(const FarmOptions& o) {
    std::vector<std::string> a;
    if (!o.resolution.empty()) a.insert(a.end(), {"--resolution", o.resolution});
    if (o.spp > 0) a.insert(a.end(), {"--spp", std::to_string(o.spp)});
    return a;
}

// The plan: the first frame's scene gives the resolution and the integrator; the frames whose
// final EXR is complete are left out with --skip-existing.
FarmPlan makePlan(const FarmOptions& o) {
    FarmPlan p;
    p.mirage = selfPath();
    p.scene = absolute(o.input);
    p.dir = absolute(o.dir.empty() ? "farm-" + fs::path(o.input).stem().string() : o.dir);
    if (p.dir.find_first_of(" \t\n'\"\\$`%") != std::string::npos)
        throw MirageError("mirage farm: --dir '" + p.dir +
                          "': no spaces, quotes, $, ` or % (Slurm's #SBATCH lines take it bare)");
    p.stem = fs::path(o.input).stem().string();
    p.tiles = parseTileGrid(o.tiles);
    p.partition = o.partition;
    p.timeLimit = o.timeLimit;
    p.cpus = o.cpus;
    p.skipExisting = o.skipExisting;

    const std::vector<int> all = parseFrameRange(o.frames);
    ColorPipeline color;
    Scene scene = loadScene(o.input, LoadOptions{all.front(), o.overrides}, color);
    FrameRequest settings;
    settings.input = o.input;
    settings.resolution = o.resolution;
    settings.spp = o.spp;
    settings.seed = o.seed;
    settings.quiet = true;
    applyFrameSettings(scene, settings);
    const std::string integrator = o.integrator.empty() ? scene.integrator : o.integrator;
    p.photons = integratorInfo(integrator).photonPass;
    for (int t = 0; t < p.tiles.count(); ++t)
        p.regions.push_back(tileWindow(p.tiles, t, scene.settings.width, scene.settings.height));
    p.sharedArgs = passThrough(o);
    p.renderOnlyArgs = renderOnly(o);
    for (int f : all)
        if (!o.skipExisting || !isCompleteFrame(farmFramePath(p, f))) p.frames.push_back(f);
    return p;
}

// Runs sbatch on a script and returns the job id (--parsable: "id" or "id;cluster").
std::string submit(const std::string& script, const std::string& dependency) {
    std::string cmd = "sbatch --parsable";
    if (!dependency.empty()) cmd += " --dependency=" + dependency;
    cmd += " " + shellQuote(script) + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) throw MirageError("mirage farm: cannot run sbatch");
    std::string out;
    char buf[256];
    while (std::fgets(buf, sizeof buf, pipe)) out += buf;
    const int status = pclose(pipe);
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
    if (status != 0 || out.empty() || out.find_first_not_of("0123456789;") != std::string::npos)
        throw MirageError("mirage farm: sbatch " + script + " failed: " +
                          (out.empty() ? "no output (is Slurm's sbatch on PATH?)" : out));
    return out.substr(0, out.find(';'));
}

std::string dependencyOf(const FarmScript& s, const std::vector<std::string>& ids) {
    std::string d;
    for (int i : s.after) d += (d.empty() ? "aftercorr:" : ":") + ids[size_t(i)];
    return d;
}

int runFarm(const FarmOptions& o) {
    const FarmPlan plan = makePlan(o);
    const std::vector<FarmScript> scripts = farmScripts(plan);
    if (plan.frames.empty()) {
        std::printf("mirage farm: every frame of %s is complete; nothing to submit\n",
                    o.frames.c_str());
        return 0;
    }
    if (o.dryRun) {
        for (const FarmScript& s : scripts) {
            std::printf("### %s/scripts/%s", plan.dir.c_str(), s.name.c_str());
            if (!s.after.empty()) {
                std::string d;
                for (int i : s.after) d += (d.empty() ? "" : ", ") + scripts[size_t(i)].name;
                std::printf("  (aftercorr: %s)", d.c_str());
            }
            std::printf("\n%s\n", s.text.c_str());
        }
        return 0;
    }
    for (const char* sub : {"scripts", "logs", "tiles", "frames", "photons"})
        fs::create_directories(plan.dir + "/" + sub);
    std::vector<std::string> ids;
    std::string summary;
    for (const FarmScript& s : scripts) {
        const std::string path = plan.dir + "/scripts/" + s.name;
        writeTextFileAtomically(path, s.text);
        ids.push_back(submit(path, dependencyOf(s, ids)));
        summary += s.name + " " + ids.back() + "\n";
    }
    writeTextFileAtomically(plan.dir + "/jobs.txt", summary);
    std::string all;
    for (const std::string& id : ids) all += (all.empty() ? "" : ",") + id;
    std::printf("%s", summary.c_str());
    std::fprintf(stderr,
                 "mirage farm: %zu frame(s) x %d tile(s) submitted; logs in %s/logs\n"
                 "  follow:  squeue -j %s\n  account: sacct -j %s -X --format=JobID,JobName,State,"
                 "ExitCode,Elapsed\n",
                 plan.frames.size(), plan.tiles.count(), plan.dir.c_str(), all.c_str(),
                 all.c_str());
    return 0;
}

// The options, in the order of --help: the shot and its farm, then those passed on to every
// task as to mirage render.
std::vector<CliOption> farmRows(FarmOptions* o) {
    return {
        {"input", "Scene .toml (or .vdb), as for mirage render", required(value(&o->input))},
        {"--frames", "Frames A to B (inclusive), e.g. 1-240", required(value(&o->frames))},
        {"--tiles",
         "Split each frame into C x R regions rendered as separate tasks (default "
         "1x1)",
         value(&o->tiles)},
        {"-d,--dir",
         "Folder of the shot: scripts/, logs/, photons/, tiles/, frames/ (default "
         "farm-<scene name>); shared by every node",
         value(&o->dir)},
        {"--partition", "Slurm partition (default: the cluster's)", value(&o->partition)},
        {"--time-limit", "Slurm time limit of each task, e.g. 2:00:00 (default: the partition's)",
         value(&o->timeLimit)},
        {"--cpus", "CPUs per task (--cpus-per-task and mirage --threads)",
         value(&o->cpus, CLI::Range(1, 4096))},
        {"--dry-run", "Print the scripts and their dependencies; submit nothing, write nothing",
         flag(&o->dryRun)},
        {"--skip-existing",
         "Leave out frames already complete; tasks skip regions and photon files "
         "already complete (a resubmitted shot renders only what is missing)",
         flag(&o->skipExisting)},
        {"--set", "Scene overrides, as for mirage render", allValues(&o->overrides)},
        {"--resolution", "Image size WxH, as for mirage render", value(&o->resolution)},
        {"--spp", "Samples per pixel, as for mirage render",
         value(&o->spp, CLI::Range(1, 1 << 20))},
        {"--seed", "Random seed, as for mirage render",
         value(&o->seed, CLI::Range(int64_t(0), INT64_MAX))},
        {"--integrator", "As for mirage render", value(&o->integrator)},
        {"--quality", "draft, preview or final, as for mirage render",
         value(&o->quality, CLI::IsMember({"draft", "preview", "final"}))},
    };
}

}  // namespace

Command addFarmCommand(CLI::App& app) {
    auto o = std::make_shared<FarmOptions>();
    auto* cmd = app.add_subcommand(
        "farm",
        "Render a shot on a Slurm farm: writes batch scripts (a photon pass per frame, a render "
        "per frame and tile, an assembly per frame) and submits them with sbatch");
    addOptions(*cmd, farmRows(o.get()));
    return {cmd, [o] { return runFarm(*o); }};
}

}  // namespace mirage
