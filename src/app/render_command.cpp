// `mirage render`: per frame, the frame request loaded and applied, rendered, and written
// (frame/), with the partial file of a killed render and --resume, and a summary at the end.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/commands.h"
#include "app/render_checkpoint.h"
#include "core/cancel.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/thread_limit.h"
#include "film/color.h"
#include "film/partial_film.h"
#include "frame/frame_output.h"
#include "frame/frame_photons.h"
#include "frame/frame_prefetch.h"
#include "render/coarse_image.h"
#include "scene/memory_budget.h"
#include "volume/load_progress.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

std::vector<int> frameList(const RenderOptions& o) {
    std::vector<int> frames;
    if (o.request.turntable > 0) {
        for (int i = 1; i <= o.request.turntable; ++i) frames.push_back(i);
    } else if (!o.frames.empty()) {
        frames = parseFrameRange(o.frames);
    } else {
        frames.push_back(o.frame >= 0 ? o.frame : 1);
    }
    return frames;
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
    // The command's stop: SIGINT and SIGTERM (core/interrupt.h), between tiles and passes.
    CancelToken cancel{CancelToken::Signals::Follow};
    bool sequence = false;  // several frames: outputs without a pattern are numbered
    int framesSkipped = 0;

    // The request of frame `frame`: the command line's, at that frame.
    FrameRequest request(int frame) const {
        FrameRequest r = o.request;
        r.frame = frame;
        r.memoryBudget = memoryBudget;
        r.sequence = sequence;
        return r;
    }
};

// Killed renders: finished tiles go to <out>.partial as they finish (rate-limited), and
// --resume starts from it when it matches this scene and these settings.
struct FrameCheckpoint {
    FrameCheckpoint(const RenderSession& rs, const LoadedFrame& job)
        : FrameCheckpoint(rs, job, partialPathFor(job.out),
                          frameFingerprint(job.scene, job.request.input, job.scene.integrator,
                                           job.request.frame, job.request.overrides)) {}

    std::string path;
    PartialFilm resumed;
    TileCheckpoint tiles;
    PassCheckpoint passes;  // a render in passes checkpoints whole passes instead of tiles
    PartialFilmWriter partial;
    bool failed = false;  // a checkpoint could not be written: off for this frame

    // The render's control: these checkpoints, and the command's stop.
    FrameControl control(const CancelToken* cancel) { return {&tiles, &passes, cancel}; }

private:
    FrameCheckpoint(const RenderSession& rs, const LoadedFrame& job, std::string partialPath,
                    const FrameFingerprint& fingerprint)
        : path(std::move(partialPath)),
          resumed(resumeIfAsked(rs.o, job, path, fingerprint)),
          partial(path, job.scene.settings.tileSize, rs.color.xyzToWorking(),
                  {{"fingerprint", fingerprint.hash},
                   {"settings", fingerprint.settings},
                   {"scene", job.scene.source},
                   {"frame", std::to_string(job.request.frame)}},
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
    static PartialFilm resumeIfAsked(const RenderOptions& o, const LoadedFrame& job,
                                     const std::string& path, const FrameFingerprint& fingerprint) {
        const RenderSettings& s = job.scene.settings;
        const bool quiet = job.request.quiet;
        if (o.resume && fs::exists(path) && !job.deep.empty())
            throw MirageError("--resume: " + path + " holds no deep samples, and the frame " +
                              "writes a deep image (" + job.deep + "); render it without --resume");
        if (o.resume && fs::exists(path))
            return loadPartialForResume(path, fingerprint, renderWindow(s).width(),
                                        renderWindow(s).height(), s.tileSize);
        if (o.resume && !quiet)
            std::fprintf(stderr, "frame %d: no %s to resume from; rendering the whole frame\n",
                         job.request.frame, path.c_str());
        else if (!o.resume && !quiet && fs::exists(path))
            std::fprintf(stderr, "frame %d: %s exists; rendering afresh (--resume continues it)\n",
                         job.request.frame, path.c_str());
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

void printFrameSummary(const LoadedFrame& job, const RenderedFrame& rendered,
                       const FrameCheckpoint& cp, double writeSeconds) {
    const RenderSettings& s = job.scene.settings;
    const RenderStats& stats = rendered.stats;
    const DroppedWork dropped = droppedWork(rendered);
    const int frame = job.request.frame;
    const int spp = framePixelSamples(job.scene, rendered);
    double mlps = stats.seconds > 0 ? stats.mediumLookups / stats.seconds / 1e6 : 0;
    std::fprintf(stderr,
                 "frame %d: %dx%d, %d spp, %llu samples | load %.2fs%s, render %.2fs, "
                 "write %.2fs | %.1f M medium lookups/s | non-finite dropped: %llu "
                 "samples, %llu photons | capped paths %llu | peak memory %s\n",
                 frame, s.width, s.height, spp, (unsigned long long)stats.samples, job.loadSeconds,
                 job.prefetched ? " (while the frame before rendered)" : "", stats.seconds,
                 writeSeconds, mlps, (unsigned long long)stats.nonFiniteSamples,
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
std::optional<int> writePhotonsOnly(const LoadedFrame& job) {
    const FrameRequest& r = job.request;
    const PhotonFrameKey key{job.scene, r.input, r.frame, r.overrides};
    if (!writeFramePhotons(key, job.scene.integrator, job.out, r.quiet)) {
        std::fprintf(stderr, "mirage: interrupted: frame %d's photon pass, nothing written\n",
                     r.frame);
        return interruptExitCode();
    }
    std::printf("%s\n", job.out.c_str());
    return std::nullopt;
}

// Renders one loaded frame and writes its preview and EXR; the exit code when the command must
// stop (interrupted), nothing to go on. Nothing loaded: the frame was complete, skipped.
std::optional<int> renderFrameFiles(RenderSession& rs, std::optional<LoadedFrame> job) {
    if (!job) {
        ++rs.framesSkipped;
        return std::nullopt;
    }
    if (job->request.photonsOnly) return writePhotonsOnly(*job);
    FrameCheckpoint cp(rs, *job);
    RenderedFrame rendered = renderFrame(job->scene, rs.color, cp.control(&rs.cancel));
    if (rendered.stats.interrupted) return stopInterrupted(cp, rendered, job->request.frame);

    const auto tWrite = Clock::now();
    writeFrame(*job, rendered, rs.color);
    // The final frame is in place (atomically): its partial file has served.
    std::error_code ec;
    fs::remove(cp.path, ec);
    const double writeSeconds = secondsSince(tWrite);

    if (!rs.o.request.quiet) printFrameSummary(*job, rendered, cp, writeSeconds);
    for (const std::string* file : {&job->out, &job->deep, &job->preview})
        if (!file->empty()) std::printf("%s\n", file->c_str());
    return std::nullopt;
}

}  // namespace

int runRender(const RenderOptions& o) {
    const auto t0 = Clock::now();
    const auto threads = limitThreads(o.threads);
    RenderSession rs(o);
    // From here a SIGINT/SIGTERM stops the render between tiles and saves what is finished.
    installInterruptHandlers();
    setGridLoadProgress(o.request.quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);

    const std::vector<int> frames = frameList(o);
    rs.sequence = frames.size() > 1;
    FramePrefetch next;  // the next frame's load, under way while this one renders
    for (size_t i = 0; i < frames.size(); ++i) {
        if (rs.cancel.requested()) break;
        std::optional<LoadedFrame> job =
            next.holds(frames[i]) ? next.take() : loadFrame(rs.request(frames[i]), rs.color);
        if (prefetchesFrames(rs.request(frames[i]), frames.size() - 1 - i, currentMemoryBytes(),
                             availableMemoryBytes()))
            next.start(rs.request(frames[i + 1]), rs.color);
        if (std::optional<int> stop = renderFrameFiles(rs, std::move(job))) return *stop;
    }
    if (rs.cancel.requested()) {
        std::fprintf(stderr, "mirage: interrupted between frames; finished frames are complete\n");
        return interruptExitCode();
    }
    if (!o.request.quiet) {
        std::string skips = rs.framesSkipped
                                ? ", " + std::to_string(rs.framesSkipped) + " skipped as complete"
                                : "";
        std::fprintf(stderr, "done: %zu frame(s) in %s%s\n", frames.size(),
                     formatSeconds(secondsSince(t0)).c_str(), skips.c_str());
    }
    return 0;
}

}  // namespace mirage
