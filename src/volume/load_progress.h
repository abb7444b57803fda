// Whether the loads of big grids show a progress bar (volume/openvdb_read.h draws it): one mode
// for the process, Quiet unless a command sets it — `mirage render` to its own bars' mode, so
// that --quiet silences both. Programs that load grids (tests, the Python module) stay quiet.
#pragma once

#include <cstdint>

#include "core/progress.h"

namespace mirage {

void setGridLoadProgress(Progress::Mode mode);
Progress::Mode gridLoadProgress();

// Grids smaller than this in the file load without a bar: they take well under a second.
constexpr uint64_t kLoadProgressBytes = uint64_t(64) << 20;

}  // namespace mirage
