// The settings a frame request lays over a loaded scene (frame_settings.h).
#include "frame/frame_settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/text.h"

namespace mirage {

void applyFrameSettings(Scene& scene, const FrameRequest& request) {
    RenderSettings& s = scene.settings;
    if (!request.resolution.empty()) {
        int w = 0, h = 0;
        char x = 0;
        if (std::sscanf(request.resolution.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' ||
            w < 1 || h < 1 || w > 65536 || h > 65536)
            throw MirageError("--resolution '" + request.resolution +
                              "': expected WxH, e.g. 640x360");
        s.width = w;
        s.height = h;
        // Keep an automatic camera framed for the new aspect ratio.
        if (isVolumeFile(request.input)) {
            const CameraDesc old = scene.render.camera;
            scene.render.camera =
                frameBounds(scene.render.bounds(), old.fovDeg, float(w) / float(h));
            scene.render.camera.shutterOpen = old.shutterOpen;
            scene.render.camera.shutterClose = old.shutterClose;
        }
    }
    if (request.spp > 0) s.spp = request.spp;
    for (const std::string& name : request.aovs)
        if (std::find(s.aovs.begin(), s.aovs.end(), name) == s.aovs.end()) s.aovs.push_back(name);
    if (!request.aovs.empty()) {
        try {
            AovLayout(s.aovs, scene.render.lightGroupNames(), scene.render.cryptoObjects);
        } catch (const MirageError& e) {
            throw MirageError(std::string("--aov: ") + e.what());
        }
    }
    if (request.seed >= 0) s.seed = uint64_t(request.seed);
    s.progress = request.quiet ? Progress::Mode::Quiet : Progress::Mode::Auto;
}

// Measured on assets/scenes/fog_sphere.toml (docs/performance.md): the fastest measured
// setting within 2.5× of relMSE 1e-1 (draft), 1e-2 (preview), 1e-3 (final); the photon preview
// and final are the best measured (relMSE 0.036 and 0.011). These hold for a scene that states
// no samples; one that does has them scaled by the scene scale (frame_settings.h). Auto's
// progressive passes on dense smoke, measured on the race scene's 16 passes of one sample
// (relMSE 0.011): 1 pass 0.11 (draft), 64 passes 0.0051 (final, the best measured).
// {name, spp, photons, k, path spp, scene scale, auto pass scale}.
const std::vector<QualityPreset>& qualityPresets() {
    static const std::vector<QualityPreset> presets = {
        {"draft", 16, 100000, 16, 64, 0.25, 1.0 / 16.0},
        {"preview", 64, 1000000, 16, 256, 1.0, 1.0},
        {"final", 256, 4000000, 16, 4096, 4.0, 4.0},
    };
    return presets;
}

const QualityPreset& qualityPreset(const std::string& name) {
    for (const auto& p : qualityPresets())
        if (p.name == name) return p;
    throw MirageError("--quality '" + name + "': expected one of " +
                      joinList(qualityPresets(), [](const QualityPreset& p) { return p.name; }));
}

void applyQualityPreset(Scene& scene, const QualityPreset& preset, const std::string& integrator,
                        const std::vector<std::string>& overrides) {
    auto overridden = [&](const std::string& key) {
        return std::any_of(overrides.begin(), overrides.end(), [&](const std::string& o) {
            return o.compare(0, key.size() + 1, key + "=") == 0;
        });
    };
    const bool photon = integratorInfo(integrator).photonPass;
    auto scaled = [&](double stated, double scale) {
        return std::max(1.0, std::round(stated * scale));
    };
    if (!overridden("film.spp"))
        scene.settings.spp = scene.statedSpp > 0 ? int(scaled(scene.statedSpp, preset.sceneScale))
                                                 : (photon ? preset.spp : preset.pathSpp);
    // A scene in passes (stated, or made by `auto` on dense smoke) scales its passes, each with
    // its own photon map, and so its samples and photons together; the photons of one map stay
    // as stated or at the default: the preset's photons are those of a one-map render.
    if (scene.statedPasses > 0 && !overridden("render.passes"))
        scene.passes.maxPasses = int(scaled(
            scene.statedPasses, scene.autoSet.passes ? preset.autoPassScale : preset.sceneScale));
    if (photon && scene.statedPasses == 0 && !overridden("render.photons"))
        scene.photon.photons =
            scene.statedPhotons > 0
                ? uint64_t(scaled(double(scene.statedPhotons), preset.sceneScale))
                : preset.photons;
    // A stated k (nonzero) is the estimate's width the scene needs (fire_smoke.toml's smoke catches
    // few photons): kept, so that the final preset is the same estimator with 4× the photons.
    if (photon && !overridden("render.k") && scene.photon.k == 0) scene.photon.k = preset.k;
}

void applyPassOptions(const FrameRequest& o, PassSettings* passes) {
    if (o.passes > 0 || o.timeLimit > 0 || o.noiseThreshold > 0) passes->maxPasses = o.passes;
    passes->timeLimit = o.timeLimit;
    passes->noiseThreshold = o.noiseThreshold;
    passes->coarseSpp = o.coarseSpp;
    if (passes->enabled() && o.passes == 0 && o.spp > 0) {
        passes->sppPerPass = std::min(passes->sppPerPass, o.spp);
        passes->maxPasses = (o.spp + passes->sppPerPass - 1) / passes->sppPerPass;
    }
}

}  // namespace mirage
