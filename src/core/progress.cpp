#include "core/progress.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>

namespace mirage {

Progress::Progress(std::string label, uint64_t total, std::string unit, Mode mode)
    : mLabel(std::move(label)), mUnit(std::move(unit)), mTotal(total ? total : 1), mMode(mode) {
    if (mMode == Mode::Auto) mMode = ::isatty(STDERR_FILENO) ? Mode::Terminal : Mode::Log;
    mStart = mLastDraw = std::chrono::steady_clock::now();
}

Progress::~Progress() { finish(); }

double Progress::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
}

void Progress::advance(uint64_t n) {
    uint64_t done = mDone.fetch_add(n) + n;
    if (mMode == Mode::Quiet) return;
    std::unique_lock<std::mutex> lock(mMutex, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is drawing; skip rather than wait
    draw(done, false);
}

void Progress::finish() {
    std::lock_guard<std::mutex> lock(mMutex);
    if (mFinished) return;
    mFinished = true;
    if (mMode != Mode::Quiet) draw(mDone.load(), true);
}

void Progress::draw(uint64_t done, bool final) {
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double>(now - mStart).count();
    double frac = std::min(1.0, double(done) / double(mTotal));
    double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
    if (mMode == Mode::Terminal) {
        if (!final && std::chrono::duration<double>(now - mLastDraw).count() < 0.1) return;
        mLastDraw = now;
        constexpr int kWidth = 30;
        int filled = int(frac * kWidth);
        std::string bar(filled, '#');
        bar.resize(kWidth, '.');
        std::fprintf(stderr, "\r%s [%s] %5.1f%%  %llu/%llu %s  %s  ETA %s   ", mLabel.c_str(),
                     bar.c_str(), frac * 100.0, (unsigned long long)done,
                     (unsigned long long)mTotal, mUnit.c_str(), formatSeconds(elapsed).c_str(),
                     final ? "0s" : formatSeconds(eta).c_str());
        if (final) std::fputc('\n', stderr);
    } else {
        int decile = int(frac * 10.0);
        if (decile == mLastDecile && !final) return;
        if (final && decile == mLastDecile) return;
        mLastDecile = decile;
        std::fprintf(stderr, "%s: %3d%% (%llu/%llu %s) elapsed %s, ETA %s\n", mLabel.c_str(),
                     decile * 10, (unsigned long long)done, (unsigned long long)mTotal,
                     mUnit.c_str(), formatSeconds(elapsed).c_str(), formatSeconds(eta).c_str());
    }
    std::fflush(stderr);
}

uint64_t peakMemoryBytes() {
    struct rusage ru {};
    ::getrusage(RUSAGE_SELF, &ru);
    return uint64_t(ru.ru_maxrss) * 1024ull;  // Linux reports kilobytes
}

std::string formatBytes(uint64_t b) {
    char buf[64];
    if (b >= (1ull << 30)) std::snprintf(buf, sizeof buf, "%.2f GiB", b / double(1ull << 30));
    else if (b >= (1ull << 20)) std::snprintf(buf, sizeof buf, "%.1f MiB", b / double(1ull << 20));
    else std::snprintf(buf, sizeof buf, "%.1f KiB", b / 1024.0);
    return buf;
}

std::string formatSeconds(double s) {
    char buf[64];
    if (s >= 3600) std::snprintf(buf, sizeof buf, "%dh%02dm", int(s / 3600), int(s / 60) % 60);
    else if (s >= 60) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s / 60), int(s) % 60);
    else std::snprintf(buf, sizeof buf, "%.1fs", s);
    return buf;
}

}  // namespace mirage
