// Radiance's RGBE picture format (.hdr, .pic; Ward, "Real Pixels", Graphics Gems II, 1991), the
// usual format of lat-long sky maps, read without OpenImageIO: OIIO took 0.05 s to decode a
// 1024 × 512 sky (2 cores, AMD EPYC) where this takes a few milliseconds, and a dome is read at
// every start of a frame. Values are RGBE's mantissa × 2^(e − 136) exactly (no half-step
// offset): what OIIO 2.4 returns, but at three exponents far outside a sky's range where it is
// one ulp low, so a sky renders the same bits whichever reader took it.
#pragma once

#include <string>
#include <vector>

namespace mirage {

struct RadianceHdr {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 × width × height, row-major from the top row
};

// Reads `path` as an RGBE picture in the standard orientation (-Y height +X width) with
// run-length encoded (1991) or flat scanlines. false: not such a file (another format, XYZE,
// another orientation), for a general reader to try; throws MirageError naming the file when it
// is one but is truncated or corrupt.
bool readRadianceHdr(const std::string& path, RadianceHdr* out);

}  // namespace mirage
