// What a rendered frame becomes (frame_load.h, render_frame.h): its image in the output colour
// space, the EXR header `mirage render` writes (colour tags and every mirage:* key, filled in
// from the render's statistics; film/exr_header.h holds what needs no render or scene), and the
// files: preview, deep image, EXR. The command line and a program rendering in code get the
// same image, header and files from here.
#pragma once

#include <cstdint>
#include <string>

#include "film/image_io.h"
#include "frame/frame_load.h"
#include "frame/render_frame.h"

namespace mirage {

class ColorPipeline;

// The samples per pixel of the frame: film.spp, or in a render in passes the most a pixel took.
int framePixelSamples(const Scene& scene, const RenderedFrame& rendered);

// Every photon the guards dropped, and every path a cap cut, both passes.
struct DroppedWork {
    uint64_t nonFinitePhotons = 0, cappedPaths = 0;
};
DroppedWork droppedWork(const RenderedFrame& rendered);

// The frame's EXR header as `mirage render` writes it, but for the deep image's keys
// (mirage:deep_*), which writeFrame adds once the deep image is written.
ExrOptions frameHeader(const LoadedFrame& frame, const RenderedFrame& rendered,
                       const ColorPipeline& color);

// The frame's image as its EXR holds it: the developed image and its layers, converted into
// the scene's output colour space ([output] color_space; the working space by default).
Image outputImage(const LoadedFrame& frame, const RenderedFrame& rendered,
                  const ColorPipeline& color);

// Writes the frame's files as `mirage render` does, each atomically: the preview (through the
// scene's display and view), the deep image, then the EXR, whose mirage:complete marks the
// frame done. Converts rendered.image into the output colour space on the way. Returns the
// header written.
ExrOptions writeFrame(const LoadedFrame& frame, RenderedFrame& rendered,
                      const ColorPipeline& color);

}  // namespace mirage
