// What ties a file to the frame that made it: the settings that decide a frame's pixels and the
// fingerprint over them, the scene file and its grid files. A partial file (--resume), a region's
// EXR (mirage assemble) and a photon file (--photons-file) each carry one and are refused by a
// frame that does not match it.
#pragma once

#include <string>
#include <vector>

namespace mirage {

struct Scene;

// The settings that decide a frame's pixels, as "key=value" lines (sorted by key), and the
// fingerprint: FNV-1a 64 of those lines, the scene file's text, and each grid file's size and
// modification time, in hex (a scene held in memory, sceneText: that text). A resumed render
// must match both. withRegion = false: the fingerprint of the whole frame a region belongs to
// (every tile of a frame agrees on it).
struct FrameFingerprint {
    std::string settings;
    std::string hash;
};
FrameFingerprint frameFingerprint(const Scene& scene, const std::string& input,
                                  const std::string& integrator, int frame,
                                  const std::vector<std::string>& overrides, bool withRegion = true,
                                  const std::string& sceneText = "");
// The same for what decides a frame's photon pass (`mirage photons`, --photons-file): the scene
// and grid files, the frame, the seed, photons, bounce cap and shutter, and the --set keys
// other than film.* and output.*. Resolution, samples and the estimate do not enter.
FrameFingerprint photonFingerprint(const Scene& scene, const std::string& input, int frame,
                                   const std::vector<std::string>& overrides);

}  // namespace mirage
