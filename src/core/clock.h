// Wall-clock time of a stage of the work (a frame, a pass, a photon map), in seconds, from the
// monotonic clock: the figures of the summaries and of the EXR header (mirage:*_seconds).
#pragma once

#include <chrono>

namespace mirage {

using Clock = std::chrono::steady_clock;

// Seconds from `t0` to now.
inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace mirage
