// A rendered frame's image, header and files (frame_output.h).
#include "frame/frame_output.h"

#include <cstdio>
#include <filesystem>

#include "core/progress.h"
#include "film/color.h"
#include "film/exr_header.h"
#include "frame/frame_fingerprint.h"
#include "frame/frame_regions.h"
#include "render/coarse_image.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

// What the frame is and what the render measured: the scene, seed, samples and frame, the
// integrator and its choice, the times (mirage:frame_seconds: from the integrator's set-up —
// photon pass, light guide — to the developed image, what a user waits for once the scene is
// loaded), and what the guards dropped and the caps cut.
void addRenderMetadata(const LoadedFrame& frame, const RenderedFrame& rendered,
                       std::map<std::string, std::string>* m) {
    const Scene& scene = frame.scene;
    const RenderStats& stats = rendered.stats;
    const DroppedWork dropped = droppedWork(rendered);
    (*m)["scene"] = scene.source;
    (*m)["seed"] = std::to_string(scene.settings.seed);
    (*m)["spp"] = std::to_string(framePixelSamples(scene, rendered));
    (*m)["frame"] = std::to_string(frame.request.frame);
    (*m)["integrator"] = rendered.integrator->name();
    (*m)["render_seconds"] = std::to_string(stats.seconds);
    (*m)["frame_seconds"] = std::to_string(rendered.seconds);
    (*m)["nonfinite_render"] = std::to_string(stats.nonFiniteSamples);
    (*m)["nonfinite_photons"] = std::to_string(dropped.nonFinitePhotons);
    (*m)["capped_paths"] = std::to_string(dropped.cappedPaths);
    if (!scene.integratorWhy.empty()) (*m)["integrator_choice"] = scene.integratorWhy;
    if (stats.tilesResumed > 0) (*m)["resumed_tiles"] = std::to_string(stats.tilesResumed);
}

// Motion blur: the shutter in frames, the frame rate, and the lookups above their majorant.
void addMotionMetadata(const Scene& scene, const RenderStats& stats,
                       std::map<std::string, std::string>* m) {
    if (!scene.render.camera.motionBlur()) return;
    char shutter[64];
    std::snprintf(shutter, sizeof shutter, "%g %g", scene.shutter.open, scene.shutter.close);
    (*m)["shutter_frames"] = shutter;
    (*m)["fps"] = std::to_string(scene.output.fps);
    (*m)["above_majorant"] = std::to_string(stats.aboveMajorant);
}

// A render in passes: how far it went and why it stopped. Re-rendering with --passes <passes>
// (and the same pass_spp and noise threshold) reproduces the image bit for bit.
void addPassMetadata(const PassSettings& settings, const RenderSettings& s, const PassReport& r,
                     std::map<std::string, std::string>* m) {
    (*m)["passes"] = std::to_string(r.passes);
    (*m)["pass_spp"] = std::to_string(settings.sppPerPass);
    (*m)["samples"] = std::to_string(r.samples);
    (*m)["estimated_error"] = headerNumber(r.estimatedError);
    (*m)["stopped_by"] = r.stop;
    (*m)["time_spent"] = headerNumber(r.seconds);  // what --time-limit is compared with
    if (r.coarseSpp > 0) {                         // --coarse <coarse_spp> reproduces it
        const RenderSettings c = coarseSettings(s);
        (*m)["coarse_spp"] = std::to_string(r.coarseSpp);
        (*m)["coarse_integrator"] = r.coarseIntegrator;
        (*m)["coarse_resolution"] = std::to_string(c.width) + "x" + std::to_string(c.height);
    }
    if (settings.timeLimit > 0) (*m)["time_limit"] = headerNumber(settings.timeLimit);
    if (settings.noiseThreshold > 0)
        (*m)["noise_threshold"] = headerNumber(settings.noiseThreshold);
}

// Which frame this is, whatever region of it: `mirage assemble` joins only regions that agree
// on it. A region is the EXR's data window, the display window the whole frame.
void addFrameIdentity(const LoadedFrame& frame, ExrOptions* exr) {
    const FrameRequest& r = frame.request;
    const RenderSettings& s = frame.scene.settings;
    exr->metadata["fingerprint"] = frameFingerprint(frame.scene, r.input, frame.scene.integrator,
                                                    r.frame, r.overrides, false, r.sceneText)
                                       .hash;
    if (s.region.empty()) return;
    exr->metadata["region"] = formatPixelWindow(s.region);
    exr->dataX = s.region.x0;
    exr->dataY = s.region.y0;
    exr->fullWidth = s.width;
    exr->fullHeight = s.height;
}

// The frame's deep image (film/deep.h), with the beauty's header; its samples per pixel and
// file size go into both headers and the summary.
void writeDeep(const LoadedFrame& frame, const DeepFilm& deep, ExrOptions* exr) {
    char mean[32];
    std::snprintf(mean, sizeof mean, "%.2f", deep.meanSamples());
    exr->metadata["deep_samples_mean"] = mean;
    exr->metadata["deep_samples_max"] = std::to_string(deep.maxSamples());
    writeDeepExr(frame.deep, deep, exr->halfFloat, exr->colorSpace, exr->metadata);
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(frame.deep, ec);
    exr->metadata["deep_file"] = frame.deep;
    exr->metadata["deep_file_bytes"] = std::to_string(ec ? 0 : bytes);
    if (!frame.request.quiet)
        std::fprintf(stderr, "frame %d: deep %s: %s samples per pixel (max %zu), %s\n",
                     frame.request.frame, frame.deep.c_str(), mean, deep.maxSamples(),
                     formatBytes(ec ? 0 : uint64_t(bytes)).c_str());
}

}  // namespace

int framePixelSamples(const Scene& scene, const RenderedFrame& rendered) {
    if (!rendered.passes) return scene.settings.spp;
    const PassReport& r = *rendered.passes;
    return r.coarseSpp > 0 ? r.coarseSpp : r.passes * scene.passes.sppPerPass;
}

DroppedWork droppedWork(const RenderedFrame& rendered) {
    const IntegratorStats s = rendered.integrator->stats();
    return {s.nonFinitePhotons, s.cappedPaths + rendered.stats.cappedFlights + s.cappedPhotonPaths};
}

ExrOptions frameHeader(const LoadedFrame& frame, const RenderedFrame& rendered,
                       const ColorPipeline& color) {
    const Scene& scene = frame.scene;
    ExrOptions exr = finishedFrameHeader(color, scene.output.colorSpace,
                                         !frame.request.floatExr && scene.output.halfFloat,
                                         scene.output.multipart);
    addRenderMetadata(frame, rendered, &exr.metadata);
    addMotionMetadata(scene, rendered.stats, &exr.metadata);
    if (rendered.passes)
        addPassMetadata(scene.passes, scene.settings, *rendered.passes, &exr.metadata);
    addFrameIdentity(frame, &exr);
    for (const auto& [key, value] : rendered.integrator->stats().metadata)
        exr.metadata[key] = value;
    return exr;
}

Image outputImage(const LoadedFrame& frame, const RenderedFrame& rendered,
                  const ColorPipeline& color) {
    Image image = rendered.image;
    convertToOutputSpace(color, frame.scene.output.colorSpace, &image);
    return image;
}

ExrOptions writeFrame(const LoadedFrame& frame, RenderedFrame& rendered,
                      const ColorPipeline& color) {
    const Scene& scene = frame.scene;
    if (!frame.preview.empty())
        writePreview(frame.preview, rendered.image, color, scene.output.display, scene.output.view);
    ExrOptions exr = frameHeader(frame, rendered, color);
    convertToOutputSpace(color, scene.output.colorSpace, &rendered.image);
    // The deep image before the beauty, whose mirage:complete says the frame is done.
    if (rendered.deep) writeDeep(frame, *rendered.deep, &exr);
    writeExr(frame.out, rendered.image, exr);
    return exr;
}

}  // namespace mirage
