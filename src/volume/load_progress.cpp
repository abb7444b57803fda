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

LoadStage::LoadStage(const std::string& stage, const std::string& path,
                     const std::string& gridLabel, uint64_t bytes, uint64_t total,
                     const std::string& unit)
    : Progress(stage + (path.empty() ? "" : " " + path.substr(path.find_last_of('/') + 1)) + " " +
                   gridLabel,
               total, unit,
               bytes >= kLoadProgressBytes ? gridLoadProgress() : Progress::Mode::Quiet) {
    advance(0);
}

}  // namespace mirage
