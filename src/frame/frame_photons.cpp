// A frame's photon pass saved and read again (frame_photons.h).
#include "frame/frame_photons.h"

#include <cstdio>

#include "core/clock.h"
#include "core/error.h"
#include "frame/frame_fingerprint.h"
#include "frame/render_frame.h"
#include "photon/photon_file.h"
#include "render/integrator.h"
#include "scene/scene.h"

namespace mirage {

namespace {

std::string photonFileFingerprint(const PhotonFrameKey& key) {
    return photonFingerprint(key.scene, key.input, key.frame, key.overrides).hash;
}

}  // namespace

bool writeFramePhotons(const PhotonFrameKey& key, const std::string& integrator,
                       const std::string& path, bool quiet) {
    if (!integratorInfo(integrator).photonPass)
        throw MirageError("mirage photons: the integrator '" + integrator +
                          "' traces no photons (use --integrator photon or [render] integrator "
                          "= \"photon\")");
    const auto t0 = Clock::now();
    PhotonPassResult pass =
        tracePhotonIntegratorPass(key.scene.render, photonSettingsFor(key.scene));
    if (pass.stats.interrupted) return false;
    PhotonFileHeader header;
    header.frame = uint32_t(key.frame);
    header.fingerprint = photonFileFingerprint(key);
    writePhotonFile(path, header, pass);
    if (!quiet)
        std::fprintf(
            stderr,
            "frame %d: photons: %llu traced, %llu volume + %llu surface stored | "
            "photon pass %.2fs | written in %.2fs total\n",
            key.frame, (unsigned long long)pass.stats.emitted,
            (unsigned long long)pass.maps.volume.size(),
            (unsigned long long)(pass.maps.surfaceGlobal.size() + pass.maps.surfaceCaustic.size()),
            pass.stats.seconds, secondsSince(t0));
    return true;
}

std::shared_ptr<const PhotonPassResult> readFramePhotons(const PhotonFrameKey& key,
                                                         const std::string& path) {
    PhotonFileHeader header;
    auto pass = std::make_shared<PhotonPassResult>(readPhotonFile(path, &header));
    if (header.frame != uint32_t(key.frame))
        throw MirageError(FileLoc{path, 0, 0}, "--photons-file holds the photons of frame " +
                                                   std::to_string(header.frame) +
                                                   ", not of frame " + std::to_string(key.frame));
    const std::string expected = photonFileFingerprint(key);
    if (header.fingerprint != expected)
        throw MirageError(FileLoc{path, 0, 0},
                          "--photons-file was made from another scene or other settings "
                          "(fingerprint " +
                              header.fingerprint + ", this render " + expected +
                              "): the scene or a grid file changed, or the seed, photons, "
                              "max_depth, shutter or a --set differ. Run mirage photons again.");
    return pass;
}

bool isCompletePhotonFile(const std::string& path) { return readPhotonFileHeader(path, nullptr); }

}  // namespace mirage
