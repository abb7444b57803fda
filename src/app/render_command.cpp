// `mirage render`: load → render → develop → write, per frame, with a summary at the end.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/commands.h"
#include "app/frame_photons.h"
#include "app/frame_regions.h"
#include "app/render_checkpoint.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/text.h"
#include "core/thread_limit.h"
#include "film/color.h"
#include "film/deep.h"
#include "film/image_io.h"
#include "film/partial_film.h"
#include "render/coarse_image.h"
#include "scene/memory_budget.h"
#include "scene/render_frame.h"
#include "scene/scene.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

std::vector<int> frameList(const RenderOptions& o) {
    std::vector<int> frames;
    if (o.turntable > 0) {
        for (int i = 1; i <= o.turntable; ++i) frames.push_back(i);
    } else if (!o.frames.empty()) {
        frames = parseFrameRange(o.frames);
    } else {
        frames.push_back(o.frame >= 0 ? o.frame : 1);
    }
    return frames;
}

// An output path for one frame: expand a pattern, or number the frames of a sequence.
std::string framePath(const std::string& path, int frame, bool sequence) {
    if (hasFramePattern(path)) return expandFramePattern(path, frame);
    if (!sequence) return path;
    fs::path p(path);
    char num[32];
    std::snprintf(num, sizeof num, ".%04d", frame);
    return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

// Chromaticities of a linear output space (a display-encoded space has none: empty).
std::vector<float> outputChromaticities(const std::string& config, const std::string& space) {
    try {
        return ColorPipeline(config, space).workingChromaticities();
    } catch (const MirageError&) {
        return {};
    }
}

// Checks the output colour space and preview display/view before a long render, not after.
void checkOutputSettings(const Scene& scene, const ColorPipeline& color) {
    const OutputSettings& out = scene.output;
    auto miss = findUnknownOutputName(color, out.colorSpace, out.display, out.view);
    if (!miss) return;
    const std::string what = miss->key == "view"
                                 ? "' is not a view of display '" + out.display + "'"
                                 : "' is not in the OCIO config";
    throw MirageError(scene.source + ": [output] " + miss->key + " '" + miss->value + what +
                      "; it has: " + joinList(miss->known));
}

// What the frames of one `mirage render` share.
struct RenderSession {
    explicit RenderSession(const RenderOptions& options)
        : o(options),
          color(options.ocioConfig),
          memoryBudget(options.maxMemory.empty() ? 0 : parseMemorySize(options.maxMemory)) {}

    const RenderOptions& o;
    ColorPipeline color;
    uint64_t memoryBudget;  // bytes; 0 = none
    bool sequence = false;  // several frames: outputs without a pattern are numbered
    int framesSkipped = 0;

    void skip(int frame, const std::string& out) {
        if (!o.quiet)
            std::fprintf(stderr, "frame %d: %s is complete, skipped\n", frame, out.c_str());
        ++framesSkipped;
    }
};

// One frame's scene, loaded, with the command line applied and its output checked.
struct FrameJob {
    int frame = 0;
    Scene scene;
    std::string integratorName;
    std::string out;   // the EXR
    std::string deep;  // the deep EXR; "" = none
    double loadSeconds = 0;
};

// With --max-memory, each grid is checked against the budget before it is read.
LoadOptions frameLoadOptions(const RenderSession& rs, int frame) {
    LoadOptions load{frame, rs.o.overrides};
    const double shutterWidth = rs.o.motionBlur ? 0.5 : rs.o.shutter;
    if (shutterWidth >= 0) load.shutter = ShutterFrames{-0.5 * shutterWidth, 0.5 * shutterWidth};
    if (rs.memoryBudget > 0)
        load.beforeGridLoad = [&rs](const Scene& partial, const std::string& file,
                                    const std::string& grid, uint64_t bytes) {
            int w = partial.settings.width, h = partial.settings.height;
            if (!rs.o.resolution.empty()) std::sscanf(rs.o.resolution.c_str(), "%dx%d", &w, &h);
            checkMemoryBudget(estimateBeforeGrid(file, grid, bytes, w, h), rs.memoryBudget,
                              rs.o.input, "loading grid '" + grid + "' would need");
        };
    return load;
}

// --passes, --time-limit, --noise-threshold: a render in passes (render/passes.h). An explicit
// --spp then caps the samples per pixel (whole passes: the count rounds up to a pass; fewer
// samples than a pass make one pass of that many). Any of the three replaces the passes a
// scene states ([render] passes): a time or noise target is not also cut at the scene's count.
void applyPassOptions(const RenderOptions& o, PassSettings* passes) {
    if (o.passes > 0 || o.timeLimit > 0 || o.noiseThreshold > 0) passes->maxPasses = o.passes;
    passes->timeLimit = o.timeLimit;
    passes->noiseThreshold = o.noiseThreshold;
    passes->coarseSpp = o.coarseSpp;
    if (passes->enabled() && o.passes == 0 && o.spp > 0) {
        passes->sppPerPass = std::min(passes->sppPerPass, o.spp);
        passes->maxPasses = (o.spp + passes->sppPerPass - 1) / passes->sppPerPass;
    }
}

// A complete output: a finished frame, or for `mirage photons` an intact photon file.
bool outputComplete(const RenderOptions& o, const std::string& out) {
    return o.photonsOnly ? isCompletePhotonFile(out) : isCompleteFrame(out);
}

// Loads the frame and applies the command line to it; nothing when --skip-existing finds its
// output complete.
std::optional<FrameJob> prepareFrame(RenderSession& rs, int frame) {
    const RenderOptions& o = rs.o;
    // With -o the output is known before loading: a complete frame costs no load at all.
    if (o.skipExisting && !o.output.empty()) {
        std::string out = framePath(o.output, frame, rs.sequence);
        if (outputComplete(o, out)) {
            rs.skip(frame, out);
            return std::nullopt;
        }
    }
    auto tLoad = std::chrono::steady_clock::now();
    FrameJob job;
    job.frame = frame;
    job.scene = loadScene(o.input, frameLoadOptions(rs, frame), rs.color);
    Scene& scene = job.scene;
    if (!o.integrator.empty()) {
        scene.integrator = o.integrator;
        scene.integratorWhy.clear();
        resolveAutoIntegrator(&scene);
    }
    job.integratorName = scene.integrator;
    if (!o.quality.empty())
        applyQualityPreset(scene, qualityPreset(o.quality), job.integratorName, o.overrides);
    applyFrameSettings(scene, o.input, FrameSettings{o.resolution, o.spp, o.seed, o.quiet, o.aovs});
    applyPassOptions(o, &scene.passes);
    if (!o.region.empty())
        scene.settings.region =
            parsePixelWindow(o.region, scene.settings.width, scene.settings.height);
    if (o.turntable > 0) setTurntable(&scene.render.camera, frame, o.turntable, scene.output.fps);
    checkOutputSettings(scene, rs.color);
    job.out = framePath(o.output.empty() ? scene.output.path : o.output, frame, rs.sequence);
    const std::string deep = o.deep.empty() ? scene.settings.deep.path : o.deep;
    if (!deep.empty()) {
        job.deep = framePath(deep, frame, rs.sequence);
        scene.settings.deep.path = job.deep;
        if (fs::absolute(job.deep).lexically_normal() == fs::absolute(job.out).lexically_normal())
            throw MirageError(std::string(o.deep.empty() ? "[output] deep" : "--deep") + " '" +
                              job.deep +
                              "' is the beauty's path: give the deep image a name "
                              "of its own");
    }
    if (o.skipExisting && outputComplete(o, job.out)) {
        rs.skip(frame, job.out);
        return std::nullopt;
    }
    if (rs.memoryBudget > 0) {
        MemoryEstimate estimate = estimateFrameMemory(scene, job.integratorName);
        checkMemoryBudget(estimate, rs.memoryBudget, scene.source);
        if (!o.quiet)
            std::fprintf(stderr, "frame %d: memory estimate %s (budget %s)\n", frame,
                         estimate.describe().c_str(), formatBytes(rs.memoryBudget).c_str());
    }
    job.loadSeconds = secondsSince(tLoad);
    return job;
}

// Killed renders: finished tiles go to <out>.partial as they finish (rate-limited), and
// --resume starts from it when it matches this scene and these settings.
struct FrameCheckpoint {
    FrameCheckpoint(const RenderSession& rs, const FrameJob& job)
        : FrameCheckpoint(rs, job, partialPathFor(job.out),
                          frameFingerprint(job.scene, rs.o.input, job.integratorName, job.frame,
                                           rs.o.overrides)) {}

    std::string path;
    PartialFilm resumed;
    TileCheckpoint tiles;
    PassCheckpoint passes;  // a render in passes checkpoints whole passes instead of tiles
    PartialFilmWriter partial;
    bool failed = false;  // a checkpoint could not be written: off for this frame

private:
    FrameCheckpoint(const RenderSession& rs, const FrameJob& job, std::string partialPath,
                    const FrameFingerprint& fingerprint)
        : path(std::move(partialPath)),
          resumed(resumeIfAsked(rs.o, job, path, fingerprint)),
          partial(path, job.scene.settings.tileSize, rs.color.xyzToWorking(),
                  {{"fingerprint", fingerprint.hash},
                   {"settings", fingerprint.settings},
                   {"scene", job.scene.source},
                   {"frame", std::to_string(job.frame)}},
                  partialWriteInterval()) {
        if (resumed.film) {
            tiles.initial = resumed.film.get();
            tiles.done = resumed.done;
            passes.initial = resumed.film.get();
            passes.passesDone = std::atoi(resumed.metadata["passes_done"].c_str());
            passes.secondsDone = std::atof(resumed.metadata["pass_seconds"].c_str());
        }
        passes.passFinished = [this](const Film& film, int passesDone, double seconds) {
            partial.setMetadata("passes_done", std::to_string(passesDone));
            partial.setMetadata("pass_seconds", std::to_string(seconds));
            tiles.tileFinished(film, std::vector<uint8_t>(tiles.done.size(), 1));
        };
        passes.stopAfterPasses = testStopAfterPasses();
        tiles.tileFinished = [this](const Film& film, const std::vector<uint8_t>& done) {
            if (failed) return;
            try {
                partial.tileFinished(film, done);
            } catch (const MirageError& e) {
                // A checkpoint that cannot be written costs the ability to resume, not the frame.
                failed = true;
                std::fprintf(stderr, "mirage: warning: %s (checkpointing off for this frame)\n",
                             e.what());
            }
        };
        tiles.stopAfterTiles = testStopAfterTiles();
        tiles.done.resize(size_t(tileCount(job.scene.settings)), 0);
    }

    // The partial file to continue from, with --resume; empty otherwise.
    static PartialFilm resumeIfAsked(const RenderOptions& o, const FrameJob& job,
                                     const std::string& path, const FrameFingerprint& fingerprint) {
        const RenderSettings& s = job.scene.settings;
        if (o.resume && fs::exists(path) && !job.deep.empty())
            throw MirageError("--resume: " + path + " holds no deep samples, and the frame " +
                              "writes a deep image (" + job.deep + "); render it without --resume");
        if (o.resume && fs::exists(path))
            return loadPartialForResume(path, fingerprint, renderWindow(s).width(),
                                        renderWindow(s).height(), s.tileSize);
        if (o.resume && !o.quiet)
            std::fprintf(stderr, "frame %d: no %s to resume from; rendering the whole frame\n",
                         job.frame, path.c_str());
        else if (!o.resume && !o.quiet && fs::exists(path))
            std::fprintf(stderr, "frame %d: %s exists; rendering afresh (--resume continues it)\n",
                         job.frame, path.c_str());
        return PartialFilm();
    }
};

// An interrupted render in passes: flush the whole passes it holds. Returns the exit code.
int stopInterruptedPasses(FrameCheckpoint& cp, const RenderedFrame& rendered, int frame) {
    const PassReport& r = *rendered.passes;
    if (r.passes > cp.passes.passesDone && !cp.failed) {
        try {
            cp.partial.setMetadata("passes_done", std::to_string(r.passes));
            cp.partial.setMetadata("pass_seconds", std::to_string(r.seconds));
            cp.partial.write(*rendered.film, std::vector<uint8_t>(cp.tiles.done.size(), 1));
        } catch (const MirageError& e) {
            std::fprintf(stderr, "mirage: warning: %s\n", e.what());
        }
    }
    std::fprintf(stderr,
                 "mirage: interrupted (%s): frame %d has %d whole passes, saved in %s; continue "
                 "with --resume\n",
                 interruptSignal() == SIGTERM ? "SIGTERM" : "SIGINT", frame, r.passes,
                 cp.path.c_str());
    return interruptExitCode();
}

// An interrupted frame: flush what is finished (the final EXR is not touched) and say how to
// continue. Returns the exit code.
int stopInterrupted(FrameCheckpoint& cp, const RenderedFrame& rendered, int frame) {
    if (rendered.passes) return stopInterruptedPasses(cp, rendered, frame);
    const RenderStats& stats = rendered.stats;
    if (stats.tilesDone > stats.tilesResumed && !cp.failed) {
        try {
            cp.partial.write(*rendered.film, cp.tiles.done);
        } catch (const MirageError& e) {
            std::fprintf(stderr, "mirage: warning: %s\n", e.what());
        }
    }
    int signal = interruptSignal();
    std::fprintf(stderr,
                 "mirage: interrupted (%s): frame %d has %d of %d tiles, saved in %s "
                 "(%d partial writes, %.3fs); continue with --resume\n",
                 signal == SIGTERM ? "SIGTERM" : "SIGINT", frame, stats.tilesDone, stats.tiles,
                 cp.path.c_str(), cp.partial.writes(), cp.partial.writeSeconds());
    return interruptExitCode();
}

// The samples per pixel of the frame: film.spp, or in a render in passes the most a pixel took.
int framePixelSamples(const Scene& scene, const RenderedFrame& rendered) {
    if (!rendered.passes) return scene.settings.spp;
    const PassReport& r = *rendered.passes;
    return r.coarseSpp > 0 ? r.coarseSpp : r.passes * scene.passes.sppPerPass;
}

// Every sample or photon the guards dropped, and every path a cap cut, both passes.
struct DroppedWork {
    uint64_t nonFinitePhotons = 0, cappedPaths = 0;
};

DroppedWork droppedWork(const RenderedFrame& rendered) {
    const IntegratorStats s = rendered.integrator->stats();
    return {s.nonFinitePhotons, s.cappedPaths + rendered.stats.cappedFlights + s.cappedPhotonPaths};
}

// A render in passes: how far it went and why it stopped. Re-rendering with --passes <passes>
// (and the same pass_spp and noise threshold) reproduces the image bit for bit.
void addPassMetadata(const PassSettings& settings, const RenderSettings& s, const PassReport& r,
                     std::map<std::string, std::string>* metadata) {
    auto num = [](double v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.6g", v);
        return std::string(buf);
    };
    (*metadata)["passes"] = std::to_string(r.passes);
    (*metadata)["pass_spp"] = std::to_string(settings.sppPerPass);
    (*metadata)["samples"] = std::to_string(r.samples);
    (*metadata)["estimated_error"] = num(r.estimatedError);
    (*metadata)["stopped_by"] = r.stop;
    (*metadata)["time_spent"] = num(r.seconds);  // what --time-limit is compared with
    if (r.coarseSpp > 0) {                       // --coarse <coarse_spp> reproduces it
        const RenderSettings c = coarseSettings(s);
        (*metadata)["coarse_spp"] = std::to_string(r.coarseSpp);
        (*metadata)["coarse_integrator"] = r.coarseIntegrator;
        (*metadata)["coarse_resolution"] = std::to_string(c.width) + "x" + std::to_string(c.height);
    }
    if (settings.timeLimit > 0) (*metadata)["time_limit"] = num(settings.timeLimit);
    if (settings.noiseThreshold > 0) (*metadata)["noise_threshold"] = num(settings.noiseThreshold);
}

// Converts the image into the scene's output colour space (if it names one) and fills the EXR
// header: colour tags and the frame's metadata.
ExrOptions outputExr(RenderSession& rs, const FrameJob& job, RenderedFrame& rendered) {
    const Scene& scene = job.scene;
    const RenderSettings& s = scene.settings;
    const RenderStats& stats = rendered.stats;
    const Integrator* integrator = rendered.integrator.get();
    const DroppedWork dropped = droppedWork(rendered);
    ExrOptions exr;
    exr.halfFloat = !rs.o.floatExr && scene.output.halfFloat;
    exr.multipart = scene.output.multipart;
    exr.colorSpace = rs.color.workingSpace();
    exr.chromaticities = rs.color.workingChromaticities();
    if (!scene.output.colorSpace.empty() && scene.output.colorSpace != rs.color.workingSpace()) {
        rs.color.convert(rendered.image.rgba, 4, scene.output.colorSpace);
        for (ImageLayer& layer : rendered.image.layers)
            if (layer.channels.size() == 3 && layer.convertColor)
                rs.color.convert(layer.pixels, 3, scene.output.colorSpace);
        exr.colorSpace = scene.output.colorSpace;
        exr.chromaticities = outputChromaticities(rs.o.ocioConfig, scene.output.colorSpace);
    }
    exr.metadata = {{"scene", scene.source},
                    {"seed", std::to_string(s.seed)},
                    {"spp", std::to_string(framePixelSamples(scene, rendered))},
                    {"frame", std::to_string(job.frame)},
                    {"integrator", integrator->name()},
                    {"render_seconds", std::to_string(stats.seconds)},
                    // The frame from the integrator's set-up (photon pass, light guide) to the
                    // developed image: what a user waits for once the scene is loaded.
                    {"frame_seconds", std::to_string(rendered.seconds)},
                    {"nonfinite_render", std::to_string(stats.nonFiniteSamples)},
                    {"nonfinite_photons", std::to_string(dropped.nonFinitePhotons)},
                    {"capped_paths", std::to_string(dropped.cappedPaths)},
                    {"version", MIRAGE_VERSION},
                    {"ocio_config", rs.color.configDescription()}};
    exr.metadata["complete"] = "true";  // --skip-existing trusts only this
    if (scene.render.camera.motionBlur()) {
        char shutter[64];
        std::snprintf(shutter, sizeof shutter, "%g %g", scene.shutter.open, scene.shutter.close);
        exr.metadata["shutter_frames"] = shutter;
        exr.metadata["fps"] = std::to_string(scene.output.fps);
        exr.metadata["above_majorant"] = std::to_string(stats.aboveMajorant);
    }
    if (!scene.integratorWhy.empty()) exr.metadata["integrator_choice"] = scene.integratorWhy;
    if (rendered.passes) addPassMetadata(scene.passes, s, *rendered.passes, &exr.metadata);
    if (stats.tilesResumed > 0) exr.metadata["resumed_tiles"] = std::to_string(stats.tilesResumed);
    // Which frame this is, whatever region of it: `mirage assemble` joins only regions that
    // agree on it. A region is the EXR's data window, the display window the whole frame.
    exr.metadata["fingerprint"] =
        frameFingerprint(scene, rs.o.input, job.integratorName, job.frame, rs.o.overrides, false)
            .hash;
    if (!s.region.empty()) {
        exr.metadata["region"] = formatPixelWindow(s.region);
        exr.dataX = s.region.x0;
        exr.dataY = s.region.y0;
        exr.fullWidth = s.width;
        exr.fullHeight = s.height;
    }
    for (const auto& [key, value] : integrator->stats().metadata) exr.metadata[key] = value;
    return exr;
}

void printFrameSummary(const FrameJob& job, const RenderedFrame& rendered,
                       const FrameCheckpoint& cp, double writeSeconds) {
    const RenderSettings& s = job.scene.settings;
    const RenderStats& stats = rendered.stats;
    const DroppedWork dropped = droppedWork(rendered);
    const int frame = job.frame;
    const int spp = framePixelSamples(job.scene, rendered);
    double mlps = stats.seconds > 0 ? stats.mediumLookups / stats.seconds / 1e6 : 0;
    std::fprintf(stderr,
                 "frame %d: %dx%d, %d spp, %llu samples | load %.2fs, render %.2fs, "
                 "write %.2fs | %.1f M medium lookups/s | non-finite dropped: %llu "
                 "samples, %llu photons | capped paths %llu | peak memory %s\n",
                 frame, s.width, s.height, spp, (unsigned long long)stats.samples, job.loadSeconds,
                 stats.seconds, writeSeconds, mlps, (unsigned long long)stats.nonFiniteSamples,
                 (unsigned long long)dropped.nonFinitePhotons,
                 (unsigned long long)dropped.cappedPaths, formatBytes(peakMemoryBytes()).c_str());
    if (cp.partial.writes() > 0)
        std::fprintf(stderr, "frame %d: partial file: %d writes, %.3fs (%.2f %% of render)\n",
                     frame, cp.partial.writes(), cp.partial.writeSeconds(),
                     stats.seconds > 0 ? 100.0 * cp.partial.writeSeconds() / stats.seconds : 0.0);
    const Scene& scene = job.scene;
    if (scene.render.camera.motionBlur())
        std::fprintf(stderr,
                     "frame %d: motion blur: shutter [%g, %g] frames at %g fps | lookups above "
                     "their majorant %llu\n",
                     frame, scene.shutter.open, scene.shutter.close, scene.output.fps,
                     (unsigned long long)stats.aboveMajorant);
    if (rendered.passes && rendered.passes->coarseSpp > 0) {
        const PassReport& r = *rendered.passes;
        const RenderSettings c = coarseSettings(s);
        std::fprintf(stderr,
                     "frame %d: the coarse image, %dx%d at %d spp by %s, magnified (stopped by "
                     "%s), estimated relative error %.4g\n",
                     frame, c.width, c.height, r.coarseSpp, r.coarseIntegrator.c_str(),
                     r.stop.c_str(), r.estimatedError);
    } else if (rendered.passes) {
        const PassReport& r = *rendered.passes;
        std::fprintf(
            stderr,
            "frame %d: %d passes of %d spp (stopped by %s), %llu samples (%.1f per "
            "pixel), estimated relative error %.4g, last pass %zu pixels\n",
            frame, r.passes, scene.passes.sppPerPass, r.stop.c_str(), (unsigned long long)r.samples,
            double(r.samples) / (double(s.width) * s.height), r.estimatedError, r.lastPassPixels);
    }
    std::fprintf(stderr, "frame %d: integrator %s%s\n", frame, rendered.integrator->name().c_str(),
                 scene.integratorWhy.empty() ? " (as the scene or --integrator names it)"
                                             : (" (" + scene.integratorWhy + ")").c_str());
    const std::string extra = rendered.integrator->stats().summary;
    if (!extra.empty()) std::fprintf(stderr, "frame %d: %s\n", frame, extra.c_str());
}

// `mirage photons`: the frame's photon pass alone, to its photon file.
std::optional<int> writePhotonsOnly(const RenderSession& rs, const FrameJob& job) {
    const PhotonFrameKey key{job.scene, rs.o.input, job.frame, rs.o.overrides};
    if (!writeFramePhotons(key, job.integratorName, job.out, rs.o.quiet)) {
        std::fprintf(stderr, "mirage: interrupted: frame %d's photon pass, nothing written\n",
                     job.frame);
        return interruptExitCode();
    }
    std::printf("%s\n", job.out.c_str());
    return std::nullopt;
}

// --photons-file: the frame's saved photon pass instead of tracing it again.
void attachSavedPhotons(const RenderSession& rs, FrameJob& job) {
    if (!integratorInfo(job.integratorName).photonPass)
        throw MirageError("--photons-file: the integrator '" + job.integratorName +
                          "' traces no photons");
    const std::string path = framePath(rs.o.photonsFile, job.frame, false);
    job.scene.photon.savedPass =
        readFramePhotons(PhotonFrameKey{job.scene, rs.o.input, job.frame, rs.o.overrides}, path);
}

// The frame's deep image (film/deep.h), with the beauty's header; its samples per pixel and
// file size go into both headers and the summary.
void writeDeep(const FrameJob& job, const RenderedFrame& rendered, ExrOptions& exr, bool quiet) {
    const DeepFilm& deep = *rendered.deep;
    char mean[32];
    std::snprintf(mean, sizeof mean, "%.2f", deep.meanSamples());
    exr.metadata["deep_samples_mean"] = mean;
    exr.metadata["deep_samples_max"] = std::to_string(deep.maxSamples());
    writeDeepExr(job.deep, deep, exr.halfFloat, exr.colorSpace, exr.metadata);
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(job.deep, ec);
    exr.metadata["deep_file"] = job.deep;
    exr.metadata["deep_file_bytes"] = std::to_string(ec ? 0 : bytes);
    if (!quiet)
        std::fprintf(stderr, "frame %d: deep %s: %s samples per pixel (max %zu), %s\n", job.frame,
                     job.deep.c_str(), mean, deep.maxSamples(),
                     formatBytes(ec ? 0 : uint64_t(bytes)).c_str());
}

// Renders one frame and writes its preview and EXR; the exit code when the command must stop
// (interrupted), nothing to go on.
std::optional<int> renderFrameFiles(RenderSession& rs, int frame) {
    std::optional<FrameJob> job = prepareFrame(rs, frame);
    if (!job) return std::nullopt;
    if (rs.o.photonsOnly) return writePhotonsOnly(rs, *job);
    if (!rs.o.photonsFile.empty()) attachSavedPhotons(rs, *job);
    const Scene& scene = job->scene;
    FrameCheckpoint cp(rs, *job);
    RenderedFrame rendered =
        renderFrame(scene, job->integratorName, rs.color, &cp.tiles, &cp.passes);
    if (rendered.stats.interrupted) return stopInterrupted(cp, rendered, frame);

    auto tWrite = std::chrono::steady_clock::now();
    std::string preview = rs.o.preview.empty() ? scene.output.preview : rs.o.preview;
    if (!preview.empty()) {
        preview = framePath(preview, frame, rs.sequence);
        writePreview(preview, rendered.image, rs.color, scene.output.display, scene.output.view);
    }
    ExrOptions exr = outputExr(rs, *job, rendered);
    // The deep image before the beauty, whose mirage:complete says the frame is done.
    if (rendered.deep) writeDeep(*job, rendered, exr, rs.o.quiet);
    writeExr(job->out, rendered.image, exr);
    // The final frame is in place (atomically): its partial file has served.
    std::error_code ec;
    fs::remove(cp.path, ec);
    const double writeSeconds = secondsSince(tWrite);

    if (!rs.o.quiet) printFrameSummary(*job, rendered, cp, writeSeconds);
    std::printf("%s\n", job->out.c_str());
    if (!job->deep.empty()) std::printf("%s\n", job->deep.c_str());
    if (!preview.empty()) std::printf("%s\n", preview.c_str());
    return std::nullopt;
}

}  // namespace

int runRender(const RenderOptions& o) {
    auto t0 = std::chrono::steady_clock::now();
    const auto threads = limitThreads(o.threads);
    RenderSession rs(o);
    // From here a SIGINT/SIGTERM stops the render between tiles and saves what is finished.
    installInterruptHandlers();

    const std::vector<int> frames = frameList(o);
    rs.sequence = frames.size() > 1;
    for (int frame : frames) {
        if (interruptRequested()) break;
        if (std::optional<int> stop = renderFrameFiles(rs, frame)) return *stop;
    }
    if (interruptRequested()) {
        std::fprintf(stderr, "mirage: interrupted between frames; finished frames are complete\n");
        return interruptExitCode();
    }
    if (!o.quiet) {
        std::string skips = rs.framesSkipped
                                ? ", " + std::to_string(rs.framesSkipped) + " skipped as complete"
                                : "";
        std::fprintf(stderr, "done: %zu frame(s) in %s%s\n", frames.size(),
                     formatSeconds(secondsSince(t0)).c_str(), skips.c_str());
    }
    return 0;
}

}  // namespace mirage
