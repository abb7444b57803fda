// What `mirage render` needs to survive being killed: the check of --resume against the frame's
// fingerprint (frame/frame_fingerprint.h), and the test hooks read from the environment.
#pragma once

#include <cstdint>
#include <string>

#include "film/partial_film.h"
#include "frame/frame_fingerprint.h"

namespace mirage {

// Reads `partialPath` and checks that it belongs to `fingerprint` and the frame's size and tile
// size. Throws MirageError with a clear message otherwise (naming the settings that differ).
PartialFilm loadPartialForResume(const std::string& partialPath, const FrameFingerprint& expected,
                                 int width, int height, int tileSize);

// Test hooks from the environment: MIRAGE_TEST_STOP_AFTER_TILES (raise the interrupt flag after
// N tiles; -1 when unset) and MIRAGE_PARTIAL_INTERVAL (least seconds between partial writes;
// 2 when unset).
int64_t testStopAfterTiles();
int64_t testStopAfterPasses();  // MIRAGE_TEST_STOP_AFTER_PASSES: the same after N passes
double partialWriteInterval();

}  // namespace mirage
