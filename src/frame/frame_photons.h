// A frame's photon pass saved once and read by every region of the frame: `mirage photons`
// writes it, `mirage render --photons-file` reads it (photon/photon_file.h holds the format).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace mirage {

struct Scene;
struct PhotonPassResult;

// What ties a photon file to one frame of one scene: the command's input and --set overrides
// (the fingerprint of frame_fingerprint.h), and the frame.
struct PhotonFrameKey {
    const Scene& scene;
    const std::string& input;
    int frame;
    const std::vector<std::string>& overrides;
};

// Runs the photon integrator's pass for the frame and writes it to `path` (atomically).
// Throws MirageError when `integrator` traces no photons. Returns false when an interrupt
// stopped the pass (then nothing is written).
bool writeFramePhotons(const PhotonFrameKey& key, const std::string& integrator,
                       const std::string& path, bool quiet);

// Reads `path` and checks that it was made for this frame of this scene with these settings;
// throws MirageError naming the file and the mismatch otherwise.
std::shared_ptr<const PhotonPassResult> readFramePhotons(const PhotonFrameKey& key,
                                                         const std::string& path);

// True when `path` is an intact photon file (--skip-existing).
bool isCompletePhotonFile(const std::string& path);

}  // namespace mirage
