// `mirage photons SCENE --frame N -o N.photons`: the photon pass of a frame alone, saved for
// the regions of that frame to render from (`mirage render --photons-file`). The command runs
// the render command's frame loop (loading, --set, --seed, --quality, --shutter, $F patterns,
// --skip-existing) with photonsOnly, so a photon file is made from exactly the scene a render
// of the same options would load.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "app/frame_photons.h"
#include "app/render_checkpoint.h"
#include "core/error.h"
#include "photon/photon_file.h"
#include "render/integrator.h"
#include "scene/render_frame.h"
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
    auto t0 = std::chrono::steady_clock::now();
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

Command addPhotonsCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    o->photonsOnly = true;
    auto* cmd = app.add_subcommand(
        "photons",
        "Trace a frame's photon pass alone and save it (-o N.photons) for `mirage render "
        "--photons-file`: every region of the frame then reads the same photons");
    cmd->add_option("input", o->input, "Scene .toml, or a .vdb/.nvdb")->required();
    cmd->add_option("-o,--output", o->output,
                    "The photon file; $F4, $F or #### take the frame (a sequence without a "
                    "pattern gets .#### before the extension)")
        ->required();
    cmd->add_option("--frame", o->frame, "Frame number (default 1)");
    cmd->add_option("--frames", o->frames, "Frames A to B (inclusive), e.g. 1-24")
        ->excludes("--frame");
    cmd->add_option("--set", o->overrides,
                    "Override scene values before loading, as for mirage render (the render "
                    "must be given the same)")
        ->take_all();
    cmd->add_option("--seed", o->seed, "Random seed (default: film.seed); the render must match")
        ->check(CLI::Range(int64_t(0), INT64_MAX));
    cmd->add_option("--integrator", o->integrator,
                    "An integrator with a photon pass (photon); default: the scene's");
    cmd->add_option("--quality", o->quality, "draft, preview or final: the preset's photon count")
        ->check(CLI::IsMember({"draft", "preview", "final"}));
    cmd->add_option("--shutter", o->shutter,
                    "Motion blur shutter WIDTH in frames, as for mirage render (photons sample "
                    "times in it)")
        ->check(CLI::Range(0.0, 2.0));
    cmd->add_flag("--motion-blur", o->motionBlur, "A 180° shutter (--shutter 0.5)")
        ->excludes("--shutter");
    cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    cmd->add_flag("--skip-existing", o->skipExisting,
                  "Skip frames whose photon file is already intact (size and checksum)");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress output");
    return {cmd, [o] { return runRender(*o); }};
}

}  // namespace mirage
