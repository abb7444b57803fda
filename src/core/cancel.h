// A caller's request to stop a render early (a user interface's stop button, the Python
// module's cancel), checked where a render stops cleanly: between tiles, the tiles in flight
// finishing (render/renderer.h), and between passes, a render in passes keeping its whole
// passes (render/passes.h). The command line's requests are SIGINT and SIGTERM
// (core/interrupt.h): a token made to follow them stops on them as well, and a render given no
// token follows them alone. Raising a token touches no process-wide state, so one render can be
// stopped while another goes on.
#pragma once

#include <atomic>

#include "core/interrupt.h"

namespace mirage {

class CancelToken {
public:
    enum class Signals { Ignore, Follow };
    explicit CancelToken(Signals signals = Signals::Ignore)
        : mFollowSignals(signals == Signals::Follow) {}

    // From any thread, at any time; lock-free.
    void cancel() { mCancelled.store(true, std::memory_order_relaxed); }
    void reset() { mCancelled.store(false, std::memory_order_relaxed); }
    bool requested() const {
        return mCancelled.load(std::memory_order_relaxed) ||
               (mFollowSignals && interruptRequested());
    }

private:
    std::atomic<bool> mCancelled{false};
    bool mFollowSignals;
};

// Whether a render should stop: `token` raised, or with no token a SIGINT or SIGTERM.
inline bool stopRequested(const CancelToken* token) {
    return token ? token->requested() : interruptRequested();
}

}  // namespace mirage
