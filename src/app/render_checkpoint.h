// What `mirage render` needs to survive being killed: the fingerprint that ties a partial file
// to the scene and settings that made it, the checks of --resume and --skip-existing, and the
// test hooks read from the environment.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "film/exr_header.h"
#include "film/partial_film.h"

namespace mirage {

struct Scene;

// The settings that decide a frame's pixels, as "key=value" lines (sorted by key), and the
// fingerprint: FNV-1a 64 of those lines, the scene file's text, and each grid file's size and
// modification time, in hex. A resumed render must match both. withRegion = false: the
// fingerprint of the whole frame a region belongs to (every tile of a frame agrees on it).
struct FrameFingerprint {
    std::string settings;
    std::string hash;
};
FrameFingerprint frameFingerprint(const Scene& scene, const std::string& input,
                                  const std::string& integrator, int frame,
                                  const std::vector<std::string>& overrides,
                                  bool withRegion = true);
// The same for what decides a frame's photon pass (`mirage photons`, --photons-file): the scene
// and grid files, the frame, the seed, photons, bounce cap and shutter, and the --set keys
// other than film.* and output.*. Resolution, samples and the estimate do not enter.
FrameFingerprint photonFingerprint(const Scene& scene, const std::string& input, int frame,
                                   const std::vector<std::string>& overrides);

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
