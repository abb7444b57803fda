// A frame request loaded and applied once (frame_load.h).
#include "frame/frame_load.h"

#include <cstdio>
#include <filesystem>

#include "core/clock.h"
#include "core/error.h"
#include "core/text.h"
#include "film/color.h"
#include "film/exr_header.h"
#include "frame/frame_photons.h"
#include "frame/frame_regions.h"
#include "frame/frame_settings.h"
#include "scene/memory_budget.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

// The loader's options: the frame, the --set keys, the integrator and the shutter; with a
// memory budget, each grid is checked against it before it is read.
LoadOptions loadOptions(const FrameRequest& r) {
    LoadOptions load{r.frame, r.overrides};
    load.integrator = r.integrator;
    load.text = r.sceneText;
    const double shutterWidth = r.motionBlur ? 0.5 : r.shutter;
    if (shutterWidth >= 0) load.shutter = ShutterFrames{-0.5 * shutterWidth, 0.5 * shutterWidth};
    if (r.memoryBudget > 0)
        load.beforeGridLoad = [&r](const Scene& partial, const std::string& file,
                                   const std::string& grid, GridPrecision precision,
                                   uint64_t bytes) {
            int w = partial.settings.width, h = partial.settings.height;
            if (!r.resolution.empty()) std::sscanf(r.resolution.c_str(), "%dx%d", &w, &h);
            checkMemoryBudget(estimateBeforeGrid(file, grid, precision, bytes, w, h),
                              r.memoryBudget, r.input, "loading grid '" + grid + "' would need");
        };
    return load;
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

// The request's settings over the loaded scene, in the order the command line has them.
void applyRequest(const FrameRequest& r, const ColorPipeline& color, Scene* scene) {
    if (!r.quality.empty())
        applyQualityPreset(*scene, qualityPreset(r.quality), scene->integrator, r.overrides);
    applyFrameSettings(*scene, r);
    applyPassOptions(r, &scene->passes);
    RenderSettings& s = scene->settings;
    if (!r.region.empty()) s.region = parsePixelWindow(r.region, s.width, s.height);
    if (r.turntable > 0)
        setTurntable(&scene->render.camera, r.frame, r.turntable, scene->output.fps);
    checkOutputSettings(*scene, color);
}

// The frame's file names: the request's, else the scene's, each with its frame number.
void nameOutputs(LoadedFrame* f) {
    const FrameRequest& r = f->request;
    Scene& scene = f->scene;
    f->out = framePath(r.output.empty() ? scene.output.path : r.output, r.frame, r.sequence);
    const std::string deep = r.deep.empty() ? scene.settings.deep.path : r.deep;
    if (!deep.empty()) {
        f->deep = framePath(deep, r.frame, r.sequence);
        scene.settings.deep.path = f->deep;
        if (fs::absolute(f->deep).lexically_normal() == fs::absolute(f->out).lexically_normal())
            throw MirageError(std::string(r.deep.empty() ? "[output] deep" : "--deep") + " '" +
                              f->deep +
                              "' is the beauty's path: give the deep image a name "
                              "of its own");
    }
    const std::string preview = r.preview.empty() ? scene.output.preview : r.preview;
    if (!preview.empty()) f->preview = framePath(preview, r.frame, r.sequence);
}

// With --skip-existing: whether `out` is complete already (a finished frame, or for `mirage
// photons` an intact photon file), and then the frame is skipped.
bool skipComplete(const FrameRequest& r, const std::string& out) {
    if (!r.skipExisting || !(r.photonsOnly ? isCompletePhotonFile(out) : isCompleteFrame(out)))
        return false;
    if (!r.quiet) std::fprintf(stderr, "frame %d: %s is complete, skipped\n", r.frame, out.c_str());
    return true;
}

// --max-memory: the loaded frame's estimate against the budget.
void checkFrameMemory(const LoadedFrame& f) {
    const FrameRequest& r = f.request;
    if (r.memoryBudget == 0) return;
    const MemoryEstimate estimate = estimateFrameMemory(f.scene, f.scene.integrator);
    checkMemoryBudget(estimate, r.memoryBudget, f.scene.source);
    if (!r.quiet)
        std::fprintf(stderr, "frame %d: memory estimate %s (budget %s)\n", r.frame,
                     estimate.describe().c_str(), formatBytes(r.memoryBudget).c_str());
}

// --photons-file: the frame's saved photon pass instead of tracing it again.
void attachSavedPhotons(LoadedFrame* f) {
    const FrameRequest& r = f->request;
    Scene& scene = f->scene;
    if (!integratorInfo(scene.integrator).photonPass)
        throw MirageError("--photons-file: the integrator '" + scene.integrator +
                          "' traces no photons");
    const std::string path = framePath(r.photonsFile, r.frame, false);
    scene.photon.savedPass =
        readFramePhotons(PhotonFrameKey{scene, r.input, r.frame, r.overrides}, path);
}

}  // namespace

std::optional<LoadedFrame> loadFrame(const FrameRequest& request, const ColorPipeline& color,
                                     GridCache* grids) {
    checkFrameRequest(request);
    // With -o the output is known before loading: a complete frame costs no load at all.
    if (!request.output.empty() &&
        skipComplete(request, framePath(request.output, request.frame, request.sequence)))
        return std::nullopt;
    const auto t0 = Clock::now();
    LoadedFrame f;
    f.request = request;
    LoadOptions load = loadOptions(f.request);
    load.grids = grids;
    f.scene = loadScene(request.input, load, color);
    applyRequest(f.request, color, &f.scene);
    nameOutputs(&f);
    if (skipComplete(f.request, f.out)) return std::nullopt;
    checkFrameMemory(f);
    f.loadSeconds = secondsSince(t0);
    if (!request.photonsFile.empty()) attachSavedPhotons(&f);
    return f;
}

}  // namespace mirage
