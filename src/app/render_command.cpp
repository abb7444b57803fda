// `mirage render`: load → render → develop → write, per frame, with a summary at the end.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands.h"
#include "app/render_checkpoint.h"
#include "app/render_frame.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "film/color.h"
#include "film/image_io.h"
#include "film/partial_film.h"
#include "scene/memory_budget.h"
#include "scene/scene.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

std::vector<int> frameList(const RenderOptions& o) {
    std::vector<int> frames;
    if (o.turntable > 0) {
        for (int i = 1; i <= o.turntable; ++i) frames.push_back(i);
    } else if (!o.frames.empty()) {
        int a = 0, b = 0;
        char dash = 0;
        if (std::sscanf(o.frames.c_str(), "%d%c%d", &a, &dash, &b) != 3 || dash != '-' || b < a)
            throw MirageError("--frames '" + o.frames + "': expected A-B with A ≤ B, e.g. 1-24");
        for (int f = a; f <= b; ++f) frames.push_back(f);
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
    auto list = [](const std::vector<std::string>& v) {
        std::string s;
        for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
        return s;
    };
    auto spaces = color.colorSpaces();
    if (!out.colorSpace.empty() &&
        std::find(spaces.begin(), spaces.end(), out.colorSpace) == spaces.end())
        throw MirageError(scene.source + ": [output] color_space '" + out.colorSpace +
                          "' is not in the OCIO config; it has: " + list(spaces));
    auto displays = color.displays();
    if (std::find(displays.begin(), displays.end(), out.display) == displays.end())
        throw MirageError(scene.source + ": [output] display '" + out.display +
                          "' is not in the OCIO config; it has: " + list(displays));
    auto views = color.views(out.display);
    if (std::find(views.begin(), views.end(), out.view) == views.end())
        throw MirageError(scene.source + ": [output] view '" + out.view + "' is not a view of display '" +
                          out.display + "'; it has: " + list(views));
}

}  // namespace

int runRender(const RenderOptions& o) {
    auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<tbb::global_control> threads;
    if (o.threads > 0)
        threads = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    ColorPipeline color(o.ocioConfig);
    const uint64_t memoryBudget = o.maxMemory.empty() ? 0 : parseMemorySize(o.maxMemory);
    // From here a SIGINT/SIGTERM stops the render between tiles and saves what is finished.
    installInterruptHandlers();

    std::vector<int> frames = frameList(o);
    bool sequence = frames.size() > 1;
    int framesSkipped = 0;
    auto skipped = [&](int frame, const std::string& out) {
        if (!o.quiet)
            std::fprintf(stderr, "frame %d: %s is complete, skipped\n", frame, out.c_str());
        ++framesSkipped;
    };
    for (int frame : frames) {
        if (interruptRequested()) break;
        // With -o the output is known before loading: a complete frame costs no load at all.
        if (o.skipExisting && !o.output.empty()) {
            std::string out = framePath(o.output, frame, sequence);
            if (isCompleteFrame(out)) {
                skipped(frame, out);
                continue;
            }
        }
        auto tLoad = std::chrono::steady_clock::now();
        LoadOptions load{frame, o.overrides};
        const double shutterWidth = o.motionBlur ? 0.5 : o.shutter;
        if (shutterWidth >= 0) load.shutter = ShutterFrames{-0.5 * shutterWidth, 0.5 * shutterWidth};
        if (memoryBudget > 0)
            load.beforeGridLoad = [&](const Scene& partial, const std::string& file,
                                      const std::string& grid, uint64_t bytes) {
                int w = partial.settings.width, h = partial.settings.height;
                if (!o.resolution.empty()) std::sscanf(o.resolution.c_str(), "%dx%d", &w, &h);
                checkMemoryBudget(estimateBeforeGrid(file, grid, bytes, w, h), memoryBudget,
                                  o.input, "loading grid '" + grid + "' would need");
            };
        Scene scene = loadScene(o.input, load, color);
        RenderSettings& s = scene.settings;
        std::string integratorName = o.integrator.empty() ? scene.integrator : o.integrator;
        if (!o.quality.empty())
            applyQualityPreset(scene, qualityPreset(o.quality), integratorName, o.overrides);
        applyFrameSettings(scene, o.input, FrameSettings{o.resolution, o.spp, o.seed, o.quiet});
        if (o.turntable > 0)
            scene.render.camera =
                orbitCamera(scene.render.camera, 360.f * float(frame - 1) / float(o.turntable));
        checkOutputSettings(scene, color);
        std::string out =
            framePath(o.output.empty() ? scene.output.path : o.output, frame, sequence);
        if (o.skipExisting && isCompleteFrame(out)) {
            skipped(frame, out);
            continue;
        }
        if (memoryBudget > 0) {
            MemoryEstimate estimate = estimateFrameMemory(scene, integratorName);
            checkMemoryBudget(estimate, memoryBudget, scene.source);
            if (!o.quiet)
                std::fprintf(stderr, "frame %d: memory estimate %s (budget %s)\n", frame,
                             estimate.describe().c_str(), formatBytes(memoryBudget).c_str());
        }
        double loadSeconds = secondsSince(tLoad);

        // Killed renders: finished tiles go to <out>.partial as they finish (rate-limited),
        // and --resume starts from it when it matches this scene and these settings.
        const std::string partialPath = partialPathFor(out);
        FrameFingerprint fingerprint =
            frameFingerprint(scene, o.input, integratorName, frame, o.overrides);
        PartialFilm resumed;
        TileCheckpoint checkpoint;
        if (o.resume && fs::exists(partialPath)) {
            resumed = loadPartialForResume(partialPath, fingerprint, s.width, s.height, s.tileSize);
            checkpoint.initial = resumed.film.get();
            checkpoint.done = resumed.done;
        } else if (o.resume && !o.quiet) {
            std::fprintf(stderr, "frame %d: no %s to resume from; rendering the whole frame\n",
                         frame, partialPath.c_str());
        } else if (!o.resume && !o.quiet && fs::exists(partialPath)) {
            std::fprintf(stderr, "frame %d: %s exists; rendering afresh (--resume continues it)\n",
                         frame, partialPath.c_str());
        }
        PartialFilmWriter partial(partialPath, s.tileSize, color.xyzToWorking(),
                                  {{"fingerprint", fingerprint.hash},
                                   {"settings", fingerprint.settings},
                                   {"scene", scene.source},
                                   {"frame", std::to_string(frame)}},
                                  partialWriteInterval());
        bool partialFailed = false;
        checkpoint.tileFinished = [&](const Film& film, const std::vector<uint8_t>& done) {
            if (partialFailed) return;
            try {
                partial.tileFinished(film, done);
            } catch (const MirageError& e) {
                // A checkpoint that cannot be written costs the ability to resume, not the frame.
                partialFailed = true;
                std::fprintf(stderr, "mirage: warning: %s (checkpointing off for this frame)\n",
                             e.what());
            }
        };
        checkpoint.stopAfterTiles = testStopAfterTiles();

        RenderedFrame rendered = renderFrame(scene, integratorName, color, &checkpoint);
        const RenderStats& stats = rendered.stats;
        if (stats.interrupted) {
            // Flush what is finished; the final EXR is not touched.
            if (stats.tilesDone > stats.tilesResumed && !partialFailed) {
                try {
                    partial.write(*rendered.film, checkpoint.done);
                } catch (const MirageError& e) {
                    std::fprintf(stderr, "mirage: warning: %s\n", e.what());
                }
            }
            int signal = interruptSignal();
            std::fprintf(stderr,
                         "mirage: interrupted (%s): frame %d has %d of %d tiles, saved in %s "
                         "(%d partial writes, %.3fs); continue with --resume\n",
                         signal == SIGTERM ? "SIGTERM" : "SIGINT", frame, stats.tilesDone,
                         stats.tiles, partialPath.c_str(), partial.writes(),
                         partial.writeSeconds());
            return interruptExitCode();
        }
        const Integrator* integrator = rendered.integrator.get();
        // Every sample or photon the guards dropped, and every path a cap cut, both passes.
        const uint64_t nonFinitePhotons = integrator->nonFinitePhotons();
        const uint64_t cappedPaths =
            integrator->cappedPaths() + stats.cappedFlights + integrator->cappedPhotonPaths();
        Image& image = rendered.image;

        auto tWrite = std::chrono::steady_clock::now();
        std::string preview = o.preview.empty() ? scene.output.preview : o.preview;
        if (!preview.empty()) {
            preview = framePath(preview, frame, sequence);
            writePreview(preview, image, color, scene.output.display, scene.output.view);
        }
        ExrOptions exr;
        exr.halfFloat = !o.floatExr && scene.output.halfFloat;
        exr.colorSpace = color.workingSpace();
        exr.chromaticities = color.workingChromaticities();
        if (!scene.output.colorSpace.empty() && scene.output.colorSpace != color.workingSpace()) {
            color.convert(image.rgba, 4, scene.output.colorSpace);
            exr.colorSpace = scene.output.colorSpace;
            exr.chromaticities = outputChromaticities(o.ocioConfig, scene.output.colorSpace);
        }
        exr.metadata = {{"scene", scene.source},
                        {"seed", std::to_string(s.seed)},
                        {"spp", std::to_string(s.spp)},
                        {"frame", std::to_string(frame)},
                        {"integrator", integrator->name()},
                        {"render_seconds", std::to_string(stats.seconds)},
                        {"nonfinite_render", std::to_string(stats.nonFiniteSamples)},
                        {"nonfinite_photons", std::to_string(nonFinitePhotons)},
                        {"capped_paths", std::to_string(cappedPaths)},
                        {"version", MIRAGE_VERSION},
                        {"ocio_config", color.configDescription()}};
        exr.metadata["complete"] = "true";  // --skip-existing trusts only this
        if (scene.render.camera.motionBlur()) {
            char shutter[64];
            std::snprintf(shutter, sizeof shutter, "%g %g", scene.shutter.open,
                          scene.shutter.close);
            exr.metadata["shutter_frames"] = shutter;
            exr.metadata["fps"] = std::to_string(scene.output.fps);
            exr.metadata["above_majorant"] = std::to_string(stats.aboveMajorant);
        }
        if (stats.tilesResumed > 0)
            exr.metadata["resumed_tiles"] = std::to_string(stats.tilesResumed);
        if (const PhotonStats* photon = integrator->photonStats())
            for (const auto& [key, value] : photon->metadata()) exr.metadata[key] = value;
        writeExr(out, image, exr);
        // The final frame is in place (atomically): its partial file has served.
        std::error_code ec;
        fs::remove(partialPath, ec);
        double writeSeconds = secondsSince(tWrite);

        if (!o.quiet) {
            double mlps = stats.seconds > 0 ? stats.mediumLookups / stats.seconds / 1e6 : 0;
            std::fprintf(stderr,
                         "frame %d: %dx%d, %d spp, %llu samples | load %.2fs, render %.2fs, "
                         "write %.2fs | %.1f M medium lookups/s | non-finite dropped: %llu "
                         "samples, %llu photons | capped paths %llu | peak memory %s\n",
                         frame, s.width, s.height, s.spp, (unsigned long long)stats.samples,
                         loadSeconds, stats.seconds, writeSeconds, mlps,
                         (unsigned long long)stats.nonFiniteSamples,
                         (unsigned long long)nonFinitePhotons, (unsigned long long)cappedPaths,
                         formatBytes(peakMemoryBytes()).c_str());
            if (partial.writes() > 0)
                std::fprintf(
                    stderr, "frame %d: partial file: %d writes, %.3fs (%.2f %% of render)\n",
                    frame, partial.writes(), partial.writeSeconds(),
                    stats.seconds > 0 ? 100.0 * partial.writeSeconds() / stats.seconds : 0.0);
            if (scene.render.camera.motionBlur())
                std::fprintf(stderr,
                             "frame %d: motion blur: shutter [%g, %g] frames at %g fps | lookups "
                             "above their majorant %llu\n",
                             frame, scene.shutter.open, scene.shutter.close, scene.output.fps,
                             (unsigned long long)stats.aboveMajorant);
            std::string extra = integrator->summary();
            if (!extra.empty()) std::fprintf(stderr, "frame %d: %s\n", frame, extra.c_str());
        }
        std::printf("%s\n", out.c_str());
        if (!preview.empty()) std::printf("%s\n", preview.c_str());
    }
    if (interruptRequested()) {
        std::fprintf(stderr, "mirage: interrupted between frames; finished frames are complete\n");
        return interruptExitCode();
    }
    if (!o.quiet) {
        std::string skips =
            framesSkipped ? ", " + std::to_string(framesSkipped) + " skipped as complete" : "";
        std::fprintf(stderr, "done: %zu frame(s) in %s%s\n", frames.size(),
                     formatSeconds(secondsSince(t0)).c_str(), skips.c_str());
    }
    return 0;
}

}  // namespace mirage
