#include "volume/load_progress.h"

#include <atomic>

namespace mirage {

namespace {
std::atomic<Progress::Mode> gMode{Progress::Mode::Quiet};
thread_local bool tQuiet = false;
}  // namespace

void setGridLoadProgress(Progress::Mode mode) { gMode = mode; }
Progress::Mode gridLoadProgress() { return tQuiet ? Progress::Mode::Quiet : gMode.load(); }

QuietGridLoads::QuietGridLoads() : mWasQuiet(tQuiet) { tQuiet = true; }
QuietGridLoads::~QuietGridLoads() { tQuiet = mWasQuiet; }

}  // namespace mirage
