// Whether the loads of big grids show a progress bar (volume/openvdb_read.h draws it): one mode
// for the process, Quiet unless a command sets it — `mirage render` to its own bars' mode, so
// that --quiet silences both. Programs that load grids (tests, the Python module) stay quiet.
#pragma once

#include <cstdint>
#include <string>

#include "core/progress.h"

namespace mirage {

void setGridLoadProgress(Progress::Mode mode);
// The process's mode, or Quiet on a thread that holds a QuietGridLoads.
Progress::Mode gridLoadProgress();

// While it lives, loads on this thread draw no bar: the next frame of a sequence, read while
// the current one renders (frame/frame_prefetch.h), beside the render's own bar.
class QuietGridLoads {
public:
    QuietGridLoads();
    ~QuietGridLoads();
    QuietGridLoads(const QuietGridLoads&) = delete;
    QuietGridLoads& operator=(const QuietGridLoads&) = delete;

private:
    bool mWasQuiet;
};

// Grids smaller than this in the file load without a bar: they take well under a second.
constexpr uint64_t kLoadProgressBytes = uint64_t(64) << 20;

// The bar of one stage of a grid's load — "<stage> <file name> <grid>" (no file name where
// `path` is empty: a grid in memory), `total` `unit`s long
// — in the process's mode, or quiet for a grid of fewer than kLoadProgressBytes (`bytes`: its
// size in the file, or in memory). Drawn at once, at 0 %: a stage that cannot count its work
// still shows that it runs.
class LoadStage : public Progress {
public:
    LoadStage(const std::string& stage, const std::string& path, const std::string& gridLabel,
              uint64_t bytes, uint64_t total, const std::string& unit);
};

}  // namespace mirage
