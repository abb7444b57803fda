#include "volume/load_progress.h"

#include <atomic>

namespace mirage {

namespace {
std::atomic<Progress::Mode> gMode{Progress::Mode::Quiet};
}  // namespace

void setGridLoadProgress(Progress::Mode mode) { gMode = mode; }
Progress::Mode gridLoadProgress() { return gMode; }

}  // namespace mirage
