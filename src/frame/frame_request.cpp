// The frame request's checks and output paths (frame_request.h).
#include "frame/frame_request.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "render/passes.h"
#include "scene/scene.h"

namespace mirage {

namespace {

// A value the request leaves at `unset`, or one in [lo, hi].
bool inRange(double value, double unset, double lo, double hi) {
    return value == unset || (value >= lo && value <= hi);
}

void refuse(const std::string& why) { throw MirageError("frame request: " + why); }

}  // namespace

void checkFrameRequest(const FrameRequest& r) {
    if (r.input.empty()) refuse("no input: a scene .toml or a .vdb/.nvdb");
    // The ranges of app/render_options.cpp.
    if (!inRange(r.spp, 0, 1, 1 << 20)) refuse("--spp is outside [1, 1048576]");
    if (!inRange(r.turntable, 0, 1, 100000)) refuse("--turntable is outside [1, 100000]");
    if (!inRange(r.passes, 0, 1, kMaxSamplesPerPixel)) refuse("--passes is outside [1, 1048576]");
    if (!inRange(r.coarseSpp, 0, 1, kMaxSamplesPerPixel))
        refuse("--coarse is outside [1, 1048576]");
    if (!inRange(r.timeLimit, 0, 1e-3, 1e9)) refuse("--time-limit is outside [0.001, 1e9]");
    if (!inRange(r.noiseThreshold, 0, 1e-6, 10)) refuse("--noise-threshold is outside [1e-6, 10]");
    if (r.shutter > 2) refuse("--shutter is outside [0, 2]");
    // The options that exclude each other.
    const bool limited = r.timeLimit > 0 || r.noiseThreshold > 0;
    if (r.motionBlur && r.shutter >= 0) refuse("--motion-blur excludes --shutter");
    if (r.coarseSpp > 0 && (r.passes > 0 || limited))
        refuse("--coarse excludes --passes, --time-limit and --noise-threshold");
    if (!r.region.empty() && (limited || r.coarseSpp > 0))
        refuse("--region excludes --time-limit, --noise-threshold and --coarse");
}

std::string framePath(const std::string& path, int frame, bool sequence) {
    if (hasFramePattern(path)) return expandFramePattern(path, frame);
    if (!sequence) return path;
    const std::filesystem::path p(path);
    char num[32];
    std::snprintf(num, sizeof num, ".%04d", frame);
    return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

}  // namespace mirage
