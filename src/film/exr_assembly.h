// Joining the regions of a frame (`mirage render --region`, one farm task each) into the frame:
// `mirage assemble`. Every channel of every subimage (EXR part) a region carries is copied by
// name — the beauty and whatever layers (AOVs) the renderer wrote — at its own pixel type, so
// the frame holds the same bits as a whole-frame render. The regions must come from one frame
// of one scene with the same settings (mirage:fingerprint, mirage:frame, …), be complete, and
// cover the frame exactly once; otherwise a MirageError names the files and the pixels at fault.
#pragma once

#include <string>
#include <vector>

namespace mirage {

struct AssemblyReport {
    int width = 0, height = 0;  // the frame (display window)
    int subimages = 0;
    std::vector<std::string> channels;  // of the first subimage
};

// Reads `tiles`, checks them and writes the frame to `out` atomically.
AssemblyReport assembleRegions(const std::vector<std::string>& tiles, const std::string& out);

}  // namespace mirage
