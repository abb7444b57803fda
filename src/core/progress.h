// Progress reporting for long work (render tiles, photon batches). On a terminal: one line
// redrawn in place with a bar, percentage, units done and ETA. Otherwise (a farm log): a plain
// line at every 10 %. Quiet: nothing. Thread-safe; the report rate is limited so that
// reporting never shows up in a profile.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace mirage {

class Progress {
public:
    enum class Mode { Auto, Terminal, Log, Quiet };
    Progress(std::string label, uint64_t total, std::string unit, Mode mode = Mode::Auto);
    ~Progress();
    void advance(uint64_t n = 1);
    void finish();
    double elapsedSeconds() const;

private:
    void draw(uint64_t done, bool final);
    std::string mLabel, mUnit;
    uint64_t mTotal;
    Mode mMode;
    std::atomic<uint64_t> mDone{0};
    std::mutex mMutex;
    std::chrono::steady_clock::time_point mStart, mLastDraw;
    int mLastDecile = -1;
    bool mFinished = false;
};

// Peak resident memory of this process, bytes.
uint64_t peakMemoryBytes();
std::string formatBytes(uint64_t bytes);
std::string formatSeconds(double seconds);

}  // namespace mirage
