// The photon loop every photon tracer shares (the photon pass and `mirage slab`): photons
// 0 … n−1 in blocks of kBlockPhotons, the blocks in parallel, one PhotonWalk per task. A
// caller that keeps its results per block and combines them in block order gets the same
// answer for any thread count: photon i draws its numbers from its own index.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/interrupt.h"
#include "core/progress.h"
#include "photon/photon_walk.h"

namespace mirage {

// Photons per block: the unit of parallel work and of ordering. Large enough that a block
// (hundreds of microseconds at least) hides the scheduling and the PhotonWalk set-up.
constexpr uint64_t kBlockPhotons = 4096;

inline uint64_t photonBlockCount(uint64_t photons) {
    return (photons + kBlockPhotons - 1) / kBlockPhotons;
}

// Calls traceBlock(walk, block, first, last) for every block of photons [first, last), and
// advances `progress` by each. With stopOnInterrupt, Ctrl-C or SIGTERM skips the blocks not
// yet started (one block is a few ms of work), so that the process exits promptly.
template <typename F>
void forEachPhotonBlock(uint64_t photons, const std::vector<const Medium*>& media,
                        Progress& progress, bool stopOnInterrupt, F&& traceBlock) {
    tbb::parallel_for(tbb::blocked_range<uint64_t>(0, photonBlockCount(photons), 1),
                      [&](const tbb::blocked_range<uint64_t>& r) {
                          PhotonWalk walk(media);
                          for (uint64_t b = r.begin(); b != r.end(); ++b) {
                              if (stopOnInterrupt && interruptRequested()) continue;
                              const uint64_t first = b * kBlockPhotons;
                              const uint64_t last = std::min(photons, first + kBlockPhotons);
                              traceBlock(walk, b, first, last);
                              progress.advance(last - first);
                          }
                      });
}

}  // namespace mirage
