// Interrupt requests (SIGINT, SIGTERM) for long renders. The signal handler only stores the
// signal number in a lock-free atomic — the one thing a handler may do safely (POSIX
// async-signal-safety: no allocation, no locks, no stdio). The photon pass polls the flag
// between blocks of photons and skips the rest; the render pass polls it between tiles, stops
// handing out new ones, lets the tiles in flight finish, and the caller flushes the finished
// tiles to the partial file and exits 128 + signal (130 for SIGINT, 143 for SIGTERM, the
// shell's convention). The handler is installed with SA_RESETHAND: a second Ctrl-C gets the
// default action and ends the process at once.
#pragma once

namespace mirage {

// Installs the handler for SIGINT and SIGTERM (idempotent).
void installInterruptHandlers();
// Restores the default actions and clears the flag (tests).
void resetInterruptHandlers();

bool interruptRequested();
// The signal that was received (SIGINT, SIGTERM), or 0.
int interruptSignal();
// Raises the flag as if `signal` had arrived (the test hook MIRAGE_TEST_STOP_AFTER_TILES).
void requestInterrupt(int signal);
void clearInterrupt();

// The process exit status for an interrupted run: 128 + signal (130 SIGINT, 143 SIGTERM).
int interruptExitCode();

}  // namespace mirage
