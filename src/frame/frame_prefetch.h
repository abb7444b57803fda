// The next frame of a sequence, loaded on a thread of its own while the current frame renders.
// A shot is hundreds of frames of big caches (a billion voxels read in tens of seconds,
// docs/performance.md, "Production-sized caches"); reading frame N+1's grids while frame N
// renders hides that read behind the render, whose threads it shares. The load is the same
// loadFrame (frame_load.h), so the frame's bits do not change; its grid-load bar is silent
// (the render's bar is on screen), and its error, if any, is thrown when that frame's turn
// comes, after the frames before it are written.
//
// Not under a memory budget (--max-memory): the budget is checked frame by frame, and two
// frames' grids would be held at once.
#pragma once

#include <future>
#include <optional>

#include "frame/frame_load.h"

namespace mirage {

class FramePrefetch {
public:
    // Starts loading `request` through `color` (which must outlive the load).
    void start(const FrameRequest& request, const ColorPipeline& color);
    // Whether the load under way, or done, is frame `frame`'s.
    bool holds(int frame) const;
    // The loaded frame (waiting for it), as loadFrame returns it; rethrows the load's error.
    std::optional<LoadedFrame> take();

private:
    int mFrame = 0;
    std::future<std::optional<LoadedFrame>> mLoad;
};

// Whether a sequence's next frame may load during the current frame's render: more frames to
// come and no memory budget.
bool prefetchesFrames(const FrameRequest& request, size_t framesLeft);

}  // namespace mirage
