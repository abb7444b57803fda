// The fingerprints of a frame and of its photon pass (frame_fingerprint.h).
#include "frame/frame_fingerprint.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/fnv1a.h"
#include "core/text.h"
#include "film/aov.h"
#include "frame/frame_regions.h"
#include "scene/scene.h"

namespace mirage {

namespace fs = std::filesystem;

namespace {

std::string fileStamp(const std::string& path) {
    std::error_code ec;
    auto size = fs::file_size(path, ec);
    if (ec) return path + ": missing";
    auto time = fs::last_write_time(path, ec).time_since_epoch().count();
    return path + ": " + std::to_string(size) + " bytes, mtime " + std::to_string(time);
}

// The settings lines, then the scene's own text (a bare VDB: its size and time) and every grid
// file it read.
FrameFingerprint fingerprintOf(const std::map<std::string, std::string>& settings,
                               const Scene& scene, const std::string& input,
                               const std::string& sceneText = "") {
    FrameFingerprint fp;
    for (const auto& [k, v] : settings) fp.settings += k + "=" + v + "\n";
    Fnv1a h;
    h.add(fp.settings);
    if (!sceneText.empty()) {
        h.add(sceneText);
    } else if (isVolumeFile(input)) {
        h.add(fileStamp(input));
    } else {
        std::ifstream f(input, std::ios::binary);
        h.add(std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()));
    }
    for (const VolumeRecord& v : scene.volumes) h.add(fileStamp(v.file));
    fp.hash = h.hex();
    return fp;
}

std::string joinOverrides(const std::vector<std::string>& overrides, bool photonPassOnly) {
    std::string sets;
    for (const auto& o : overrides) {
        // The photon pass reads no film or output key (the seed is a line of its own).
        if (photonPassOnly && (o.rfind("film.", 0) == 0 || o.rfind("output.", 0) == 0)) continue;
        sets += (sets.empty() ? "" : " ") + o;
    }
    return sets;
}

bool hasAov(const std::vector<std::string>& aovs, const std::string& name) {
    return std::find(aovs.begin(), aovs.end(), name) != aovs.end();
}

std::string shutterText(const Scene& scene) {
    char b[64];
    std::snprintf(b, sizeof b, "%.9g %.9g", scene.render.camera.shutterOpen,
                  scene.render.camera.shutterClose);
    return b;
}

std::string vecText(const Vec3& v) {
    char b[96];
    std::snprintf(b, sizeof b, "%.9g,%.9g,%.9g", v.x, v.y, v.z);
    return b;
}

std::string poseText(const CameraPose& c) {
    char fov[32];
    std::snprintf(fov, sizeof fov, "%.9g", c.fovDeg);
    return vecText(c.position) + ";" + vecText(c.lookAt) + ";" + vecText(c.up) + ";" + fov;
}

// What moves the camera within the shutter: its keys (time in seconds, then the pose) and the
// turntable's angle and rate. The scene text holds the keys too, but the settings lines let a
// refusal name what changed, and --turntable changes the rate from the command line.
std::string cameraMotionText(const CameraDesc& c) {
    std::string keys;
    for (const CameraKey& k : c.keys) {
        char t[32];
        std::snprintf(t, sizeof t, "%.9g", k.time);
        keys += (keys.empty() ? "" : " | ") + std::string(t) + "s " + poseText(k.pose);
    }
    return keys.empty() ? "none" : keys;
}

std::string turntableText(const CameraDesc& c) {
    char b[96];
    std::snprintf(b, sizeof b, "%.9g deg, %.9g deg/s", c.orbitDegrees, c.orbitDegreesPerSecond);
    return b;
}

// Each volume's velocity grid and scale: which grid moves it and how far.
std::string velocityText(const Scene& scene) {
    std::string text;
    for (const VolumeRecord& v : scene.volumes) {
        char scale[32];
        std::snprintf(scale, sizeof scale, "%.9g", v.velocity.scale);
        text += (text.empty() ? "" : "; ") + (v.velocity.grid.empty() ? "none" : v.velocity.grid) +
                " x" + scale;
    }
    return text;
}

}  // namespace

FrameFingerprint frameFingerprint(const Scene& scene, const std::string& input,
                                  const std::string& integrator, int frame,
                                  const std::vector<std::string>& overrides, bool withRegion,
                                  const std::string& sceneText) {
    const RenderSettings& s = scene.settings;
    const CameraDesc& c = scene.render.camera;
    std::map<std::string, std::string> m;
    m["camera"] = poseText(c);
    // Motion blur: what moves within the shutter, the shutter and the frame rate.
    m["camera_keys"] = cameraMotionText(c);
    m["turntable"] = turntableText(c);
    m["shutter_seconds"] = shutterText(scene);
    char fps[32];
    std::snprintf(fps, sizeof fps, "%.9g", scene.output.fps);
    m["fps"] = fps;
    m["velocity"] = velocityText(scene);
    m["frame"] = std::to_string(frame);
    m["integrator"] = integrator;
    m["max_depth"] = std::to_string(scene.maxDepth);
    m["photons"] = std::to_string(scene.photon.photons);
    // Only where it differs, so that the fingerprints of earlier partial files still match.
    if (scene.photon.photonsOfPass(0) != scene.photon.photons)
        m["first_pass_photons"] = std::to_string(scene.photon.photonsOfPass(0));
    m["estimate"] = scene.photon.estimate == PhotonEstimate::Beam ? "beam" : "point";
    m["k"] = std::to_string(scene.photon.k);
    m["max_radius"] = std::to_string(scene.photon.maxRadius);
    m["final_gather"] = std::to_string(scene.photon.finalGather);
    m["resolution"] = std::to_string(s.width) + "x" + std::to_string(s.height);
    // A partial file holds the sums of its region only; a region's EXR says which frame it is
    // a part of (the fingerprint without the region), for `mirage assemble`.
    if (withRegion && !s.region.empty()) m["region"] = formatPixelWindow(s.region);
    m["seed"] = std::to_string(s.seed);
    m["spp"] = std::to_string(s.spp);
    m["tile_size"] = std::to_string(s.tileSize);
    // A render in passes resumes pass by pass; the samples per pass and the noise threshold
    // (which pixels each pass samples) decide its pixels, the pass cap and time limit do not.
    char passes[96] = "off";
    if (scene.passes.enabled())
        std::snprintf(passes, sizeof passes, "pass_spp %d, noise_threshold %.9g",
                      scene.passes.sppPerPass, scene.passes.noiseThreshold);
    m["passes"] = passes;
    m["version"] = MIRAGE_VERSION;
    // The passes, and the names a Cryptomatte hashes into its objects' IDs: a volume renamed
    // between runs would otherwise resume under another ID (a refusal names the change).
    if (!s.aovs.empty()) m["aovs"] = joinList(s.aovs);
    const CryptoObjects& crypto = scene.render.cryptoObjects;
    if (hasAov(s.aovs, cryptomattePass("volume"))) m["crypto_volumes"] = joinList(crypto.volumes);
    if (hasAov(s.aovs, cryptomattePass("shape"))) m["crypto_shapes"] = joinList(crypto.shapes);
    m["set"] = joinOverrides(overrides, false);
    return fingerprintOf(m, scene, input, sceneText);
}

FrameFingerprint photonFingerprint(const Scene& scene, const std::string& input, int frame,
                                   const std::vector<std::string>& overrides) {
    std::map<std::string, std::string> m;
    m["frame"] = std::to_string(frame);
    m["max_depth"] = std::to_string(scene.maxDepth);
    m["photons"] = std::to_string(scene.photon.photonsOfPass(0));  // the saved pass is pass 0
    m["seed"] = std::to_string(scene.settings.seed);
    m["shutter_seconds"] = shutterText(scene);
    m["version"] = MIRAGE_VERSION;
    m["set"] = joinOverrides(overrides, true);
    return fingerprintOf(m, scene, input);
}

}  // namespace mirage
