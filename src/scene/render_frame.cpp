#include "scene/render_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/text.h"
#include "film/color.h"
#include "render/coarse_image.h"

namespace mirage {

void applyFrameSettings(Scene& scene, const std::string& input, const FrameSettings& cli) {
    RenderSettings& s = scene.settings;
    if (!cli.resolution.empty()) {
        int w = 0, h = 0;
        char x = 0;
        if (std::sscanf(cli.resolution.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 1 ||
            h < 1 || w > 65536 || h > 65536)
            throw MirageError("--resolution '" + cli.resolution + "': expected WxH, e.g. 640x360");
        s.width = w;
        s.height = h;
        // Keep an automatic camera framed for the new aspect ratio.
        if (isVolumeFile(input)) {
            const CameraDesc old = scene.render.camera;
            scene.render.camera =
                frameBounds(scene.render.bounds(), old.fovDeg, float(w) / float(h));
            scene.render.camera.shutterOpen = old.shutterOpen;
            scene.render.camera.shutterClose = old.shutterClose;
        }
    }
    if (cli.spp > 0) s.spp = cli.spp;
    for (const std::string& name : cli.aovs)
        if (std::find(s.aovs.begin(), s.aovs.end(), name) == s.aovs.end()) s.aovs.push_back(name);
    if (!cli.aovs.empty()) {
        try {
            AovLayout(s.aovs, scene.render.lightGroupNames(), scene.render.cryptoObjects);
        } catch (const MirageError& e) {
            throw MirageError(std::string("--aov: ") + e.what());
        }
    }
    if (cli.seed >= 0) s.seed = uint64_t(cli.seed);
    s.progress = cli.quiet ? Progress::Mode::Quiet : Progress::Mode::Auto;
}

// Measured on assets/scenes/fog_sphere.toml (docs/performance.md): the fastest measured
// setting within 2.5× of relMSE 1e-1 (draft), 1e-2 (preview), 1e-3 (final); the photon preview
// and final are the best measured (relMSE 0.036 and 0.011). These hold for a scene that states
// no samples; one that does has them scaled by the scene scale (render_frame.h). Auto's
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

PhotonIntegratorSettings photonSettingsFor(const Scene& scene) {
    // The photon pass takes the render's seed and progress mode.
    PhotonIntegratorSettings photon = scene.photon;
    photon.seed = scene.settings.seed;
    photon.progress = scene.settings.progress;
    photon.maxBounces = scene.maxDepth;  // as makeIntegrator sets it
    if (scene.refraction) {
        photon.field = scene.refraction->field;
        photon.curvedPath = scene.refraction->path;
        photon.curvedMaxArc = scene.refraction->maxArc;
    }
    return photon;
}

namespace {

// What renders the coarse image (render/coarse_image.h): the frame's own integrator when it
// traces no photons; else the path tracer, which renders the same light without a photon map.
// None where camera rays curve ([refraction]): there the photon mapper takes even direct light
// from its maps, which straight shadow rays would not match. Throws MirageError for a --coarse
// that cannot be rendered.
Integrator* coarseIntegrator(const Scene& scene, Integrator& frameIntegrator,
                             std::unique_ptr<Integrator>* owned) {
    const bool asked = scene.passes.coarseSpp > 0;
    if (asked && !coarseImagePossible(scene.settings))
        throw MirageError(
            "--coarse renders the whole frame's beauty alone: not with --region "
            "or render passes (--aov, [output] aovs)");
    if (scene.refraction) {
        if (asked)
            throw MirageError(
                "--coarse needs straight camera rays; the scene bends them "
                "([refraction])");
        return nullptr;
    }
    if (!frameIntegrator.info().photonPass) return &frameIntegrator;
    *owned = makeVolPathIntegrator(scene.maxDepth);
    return owned->get();
}

}  // namespace

RenderedFrame renderFrame(const Scene& scene, const std::string& integrator,
                          const ColorPipeline& color, TileCheckpoint* checkpoint,
                          PassCheckpoint* passCheckpoint) {
    auto t0 = std::chrono::steady_clock::now();
    RenderedFrame frame;
    const RenderSettings& s = scene.settings;
    const PhotonIntegratorSettings photon = photonSettingsFor(scene);
    std::string name = integrator.empty() ? scene.integrator : integrator;
    if (name == "auto") name = chooseIntegrator(scene).name;
    frame.integrator = makeIntegrator(name, scene.maxDepth, photon);
    if (scene.refraction)
        frame.integrator =
            makeCurvedCameraIntegrator(std::move(frame.integrator), scene.refraction);
    aovLayout(scene.render, s);  // its errors before the photon pass
    if (!s.deep.path.empty()) {
        // A curved camera ray is many chords, each its own straight ray for the integrator.
        if (scene.refraction)
            throw MirageError("deep output (" + s.deep.path +
                              ") follows straight camera rays; "
                              "the scene bends them ([refraction])");
        // Deep samples are merged per pixel once, from all of its samples.
        if (scene.passes.enabled())
            throw MirageError("deep output (" + s.deep.path +
                              ") is made by one render of film.spp samples, not by a render in "
                              "passes (--passes, --time-limit, --noise-threshold, --coarse)");
        if (!s.region.empty())
            throw MirageError("deep output (" + s.deep.path +
                              ") covers the whole frame: render it without --region");
        frame.deep = std::make_unique<DeepFilm>(s.width, s.height);
    }
    // Sized by the whole frame's samples, not the region's or the passes': a frame rendered in
    // regions or in any number of passes gets the same per-frame caches, and so the same bits.
    auto prepare = [&] {
        frame.integrator->preprocess(
            scene.render, uint64_t(s.width) * uint64_t(s.height) * uint64_t(std::max(s.spp, 1)));
    };
    std::unique_ptr<Integrator> coarseOwned;
    CoarseStage coarse;
    if (scene.passes.enabled())
        coarse.integrator = coarseIntegrator(scene, *frame.integrator, &coarseOwned);
    // A coarse image by another integrator leaves the frame integrator's set-up to the first
    // full pass: a render that ends with the coarse image does not trace a photon map.
    if (coarseOwned)
        coarse.prepareFullPasses = prepare;
    else
        prepare();
    if (scene.passes.enabled()) {
        PassRun run;
        run.frameStart = t0;
        run.checkpoint = passCheckpoint;
        run.coarse = coarse;
        PassResult r = renderPasses(scene.render, *frame.integrator, s, scene.passes, run);
        frame.film = std::make_unique<Film>(std::move(r.film));
        frame.stats = r.stats;
        frame.passes = r.report;
    } else {
        frame.film = std::make_unique<Film>(render(scene.render, *frame.integrator, s, &frame.stats,
                                                   checkpoint, {}, frame.deep.get()));
    }
    frame.image = frame.film->develop(color);
    if (frame.deep) frame.deep->develop(color.xyzToWorking());
    frame.seconds = secondsSince(t0);
    return frame;
}

}  // namespace mirage
