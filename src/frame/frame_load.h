// A frame request loaded and applied once (frame_request.h): the scene file read with the
// request's frame, --set keys, shutter and integrator (the loader resolves "auto" once, with
// the request's integrator), then the quality preset, the command-line settings, the passes,
// the region and the turntable laid over it (frame_settings.h), the output colour space and
// display checked, the frame's file names fixed, the memory budget checked, and a saved photon
// pass attached. What renderFrame (render_frame.h) and writeFrame (frame_output.h) take.
#pragma once

#include <optional>
#include <string>

#include "frame/frame_request.h"
#include "scene/scene.h"

namespace mirage {

class ColorPipeline;
class GridCache;

struct LoadedFrame {
    FrameRequest request;    // as given
    Scene scene;             // the request applied; scene.integrator is resolved (never "auto")
    std::string out;         // the EXR (`mirage photons`: the photon file)
    std::string deep;        // the deep EXR; "" = none
    std::string preview;     // the display preview; "" = none
    double loadSeconds = 0;  // the load and the request's checks, wall
    bool prefetched = false;  // loaded while the frame before rendered (frame_prefetch.h)
};

// Loads and applies `request` through `color`. Nothing when request.skipExisting finds the
// frame's output complete (said on stderr unless quiet); before loading when request.output
// names it. Throws MirageError for a bad request, scene or setting, and for a frame over its
// memory budget (each grid is checked before it is read, the frame once loaded).
// `grids`, when given, keeps the frame's grids for the next load (volume/grid_cache.h).
std::optional<LoadedFrame> loadFrame(const FrameRequest& request, const ColorPipeline& color,
                                     GridCache* grids = nullptr);

}  // namespace mirage
