// The next frame of a sequence, loaded on a thread of its own while the current frame renders.
// A shot is hundreds of frames of big caches (a billion voxels read in tens of seconds,
// docs/performance.md, "Production-sized caches"); reading frame N+1's grids while frame N
// renders hides that read behind the render, whose threads it shares. The load is the same
// loadFrame (frame_load.h), so the frame's bits do not change; its grid-load bar is silent
// (the render's bar is on screen), and its error, if any, is thrown when that frame's turn
// comes, after the frames before it are written.
//
// Two frames' grids are held at once while the next loads, so it loads early only where they
// fit: not under a memory budget (--max-memory, checked frame by frame), and only while the
// memory the system can still give exceeds what this process holds now (the loaded frame, about
// what the next one needs) by a quarter. A sequence of caches too big for two at once loads
// each frame when it starts, as without prefetching.
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
// come, no memory budget, and available > 1.25 × resident (bytes; see above). The command
// passes currentMemoryBytes() and availableMemoryBytes() (scene/memory_budget.h).
bool prefetchesFrames(const FrameRequest& request, size_t framesLeft, uint64_t resident,
                      uint64_t available);

}  // namespace mirage
