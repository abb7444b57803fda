// A deliberate data race, built only under ThreadSanitizer (MIRAGE_TSAN): the proof that the
// TSan gate of pipeline/sanitize.sh can see a race. A clean TSan run means something only if
// the same build, the same TBB and the same TSAN_OPTIONS report this program; sanitize.sh
// fails when it does not.
//
// The race is the classic bug of a parallel pass: a plain counter incremented from the body of
// tbb::parallel_for, as a tally of photons or tiles would be without std::atomic or a
// per-block slot. Mirage's own passes run inside TBB tasks, so the canary does too: a race
// between two TBB tasks must be reported, however TBB's scheduler is built.
//
// Exit status: TSan's (66 with halt_on_error=1) when the race is reported; 0 if it ran on
// several threads and TSan stayed silent (the gate is blind: sanitize.sh fails); 3 if TBB ran
// every chunk on one thread, so that there was no race to see (sanitize.sh fails too, asking
// for a rerun, rather than pass a canary that proved nothing).
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <chrono>
#include <cstdio>
#include <set>
#include <thread>
#include <vector>

namespace {

// Not atomic, not guarded: the race. `volatile` keeps the compiler from folding the increments.
volatile long gRacyTally = 0;

void racyTally() { gRacyTally = gRacyTally + 1; }

}  // namespace

int main() {
    // Two threads whatever the machine, as the 1-vs-2-thread tests of the photon pass use.
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
    // 64 chunks that each sleep 2 ms: the worker thread wakes and steals long before the
    // caller could finish them all alone, even on a loaded machine.
    const int chunks = 64;
    std::vector<std::thread::id> ranOn(chunks);  // one slot per chunk: no sharing
    tbb::parallel_for(
        tbb::blocked_range<int>(0, chunks, 1),
        [&](const tbb::blocked_range<int>& r) {
            for (int c = r.begin(); c < r.end(); ++c) {
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
                ranOn[size_t(c)] = std::this_thread::get_id();
                racyTally();
            }
        },
        tbb::simple_partitioner());
    std::set<std::thread::id> distinct(ranOn.begin(), ranOn.end());
    if (distinct.size() < 2) {
        std::fprintf(stderr, "race_canary: all %d chunks ran on one thread; nothing to detect\n",
                     chunks);
        return 3;
    }
    std::fprintf(stderr,
                 "race_canary: %zu threads incremented an unguarded counter (%ld) and "
                 "ThreadSanitizer did not report it\n",
                 distinct.size(), long(gRacyTally));
    return 0;
}
