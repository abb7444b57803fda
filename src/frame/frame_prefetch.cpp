// The next frame of a sequence, loaded while the current one renders (frame_prefetch.h).
#include "frame/frame_prefetch.h"

#include "volume/load_progress.h"

namespace mirage {

void FramePrefetch::start(const FrameRequest& request, const ColorPipeline& color) {
    mFrame = request.frame;
    mLoad = std::async(std::launch::async, [request, &color] {
        QuietGridLoads quiet;
        std::optional<LoadedFrame> frame = loadFrame(request, color);
        if (frame) frame->prefetched = true;
        return frame;
    });
}

bool FramePrefetch::holds(int frame) const { return mLoad.valid() && mFrame == frame; }

std::optional<LoadedFrame> FramePrefetch::take() { return mLoad.get(); }

bool prefetchesFrames(const FrameRequest& request, size_t framesLeft, uint64_t resident,
                      uint64_t available) {
    return framesLeft > 0 && request.memoryBudget == 0 && available > resident + resident / 4;
}

}  // namespace mirage
