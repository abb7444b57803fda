// One frame of the pipeline (render_frame.h).
#include "frame/render_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "film/color.h"
#include "render/coarse_image.h"

namespace mirage {

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

// The frame's integrator: the scene's (resolved when it was loaded, never "auto"), wrapped by the
// curved camera where a [refraction] field bends camera rays.
std::unique_ptr<Integrator> frameIntegrator(const Scene& scene) {
    std::unique_ptr<Integrator> integrator =
        makeIntegrator(scene.integrator, scene.maxDepth, photonSettingsFor(scene));
    if (scene.refraction)
        integrator = makeCurvedCameraIntegrator(std::move(integrator), scene.refraction);
    return integrator;
}

// The deep film, when the frame writes a deep image; null otherwise. Throws MirageError where
// the frame cannot have one.
std::unique_ptr<DeepFilm> deepFilmFor(const Scene& scene) {
    const RenderSettings& s = scene.settings;
    if (s.deep.path.empty()) return nullptr;
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
    return std::make_unique<DeepFilm>(s.width, s.height);
}

// The render in passes of `frame`, its integrator made (render/passes.h).
void renderInPasses(const Scene& scene, const FrameControl& control, Clock::time_point t0,
                    const std::function<void()>& prepare, RenderedFrame* frame) {
    PassRun run;
    run.frameStart = t0;
    run.checkpoint = control.passes;
    run.cancel = control.cancel;
    std::unique_ptr<Integrator> coarseOwned;
    run.coarse.integrator = coarseIntegrator(scene, *frame->integrator, &coarseOwned);
    // A coarse image by another integrator leaves the frame integrator's set-up to the first
    // full pass: a render that ends with the coarse image does not trace a photon map.
    if (coarseOwned)
        run.coarse.prepareFullPasses = prepare;
    else
        prepare();
    PassResult r =
        renderPasses(scene.render, *frame->integrator, scene.settings, scene.passes, run);
    frame->film = std::make_unique<Film>(std::move(r.film));
    frame->stats = r.stats;
    frame->passes = r.report;
}

}  // namespace

RenderedFrame renderFrame(const Scene& scene, const ColorPipeline& color,
                          const FrameControl& control) {
    const auto t0 = Clock::now();
    const RenderSettings& s = scene.settings;
    RenderedFrame frame;
    frame.integrator = frameIntegrator(scene);
    aovLayout(scene.render, s);  // its errors before the photon pass
    frame.deep = deepFilmFor(scene);
    // Sized by the whole frame's samples, not the region's or the passes': a frame rendered in
    // regions or in any number of passes gets the same per-frame caches, and so the same bits.
    const auto prepare = [&] {
        frame.integrator->preprocess(
            scene.render, uint64_t(s.width) * uint64_t(s.height) * uint64_t(std::max(s.spp, 1)));
    };
    if (scene.passes.enabled()) {
        renderInPasses(scene, control, t0, prepare, &frame);
    } else {
        prepare();
        TileCheckpoint own;
        TileCheckpoint* tiles = control.tiles ? control.tiles : &own;
        if (control.cancel) tiles->cancel = control.cancel;
        frame.film = std::make_unique<Film>(
            render(scene.render, *frame.integrator, s, &frame.stats, tiles, {}, frame.deep.get()));
    }
    frame.image = frame.film->develop(color);
    if (frame.deep) frame.deep->develop(color.xyzToWorking());
    frame.seconds = secondsSince(t0);
    return frame;
}

}  // namespace mirage
