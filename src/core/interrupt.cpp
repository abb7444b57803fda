#include "core/interrupt.h"

#include <atomic>
#include <csignal>

namespace mirage {

namespace {

// Lock-free, so storing to it from a handler is async-signal-safe (C++17 [support.signal]).
std::atomic<int> gSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free");

extern "C" void onInterrupt(int signal) { gSignal.store(signal, std::memory_order_relaxed); }

bool gInstalled = false;

}  // namespace

void installInterruptHandlers() {
    if (gInstalled) return;
    struct sigaction action {};
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    // SA_RESETHAND: the second signal takes the default action (terminate) at once.
    // SA_RESTART: a write or read interrupted by the signal resumes instead of failing.
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    gInstalled = true;
}

void resetInterruptHandlers() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    gInstalled = false;
    clearInterrupt();
}

bool interruptRequested() { return gSignal.load(std::memory_order_relaxed) != 0; }
int interruptSignal() { return gSignal.load(std::memory_order_relaxed); }
void requestInterrupt(int signal) { gSignal.store(signal, std::memory_order_relaxed); }
void clearInterrupt() { gSignal.store(0, std::memory_order_relaxed); }

int interruptExitCode() {
    int s = interruptSignal();
    return s > 0 ? 128 + s : 0;
}

}  // namespace mirage
