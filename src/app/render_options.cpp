// The options of `mirage render` and their help text (docs/cli.md is the long form), as tables
// (app/cli_table.h) in the order of its --help; the command itself is runRender
// (render_command.cpp), and what they fill is the frame request of frame/frame_request.h.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>

#include "app/cli_table.h"
#include "app/commands.h"
#include "core/text.h"
#include "render/integrator.h"
#include "render/passes.h"

namespace mirage {

namespace {

// What to render, which frames, and where the image goes.
std::vector<CliOption> inputRows(RenderOptions* o) {
    FrameRequest& r = o->request;
    return {
        {"input", "Scene .toml, or a .vdb/.nvdb for a quick look", required(value(&r.input))},
        {"-o,--output",
         "Output EXR; $F4, $F or #### take the frame (a sequence without a pattern "
         "gets .#### before the extension); default: the scene's [output] path",
         value(&r.output)},
        {"--preview",
         "Also write a display preview (PNG/JPEG) through "
         "the scene's [output] display/view (default "
         "sRGB, Standard); default: the scene's preview",
         value(&r.preview)},
        {"--frame",
         "Frame number for $F/#### patterns and turntables "
         "(default 1)",
         value(&o->frame)},
        {"--frames",
         "Render frames A to B (inclusive), e.g. 1-24; A-BxS every S-th "
         "frame, e.g. 1-48x2",
         value(&o->frames),
         {"--frame"}},
        {"--set",
         "Override scene values before loading: "
         "key.path=value …, e.g. film.spp=64 "
         "volume.0.density_scale=2 (a bare VDB: film.*, "
         "render.*, output.* only)",
         allValues(&r.overrides)},
    };
}

// The image's size and samples, and the method that renders it.
std::vector<CliOption> samplingRows(RenderOptions* o) {
    FrameRequest& r = o->request;
    return {
        {"--resolution",
         "Image size WxH (overrides "
         "film.resolution; a bare VDB's camera "
         "reframes)",
         value(&r.resolution)},
        {"--spp", "Samples per pixel (overrides film.spp and --quality)",
         value(&r.spp, CLI::Range(1, 1 << 20))},
        {"--threads", "Worker threads (default: all cores)",
         value(&o->threads, CLI::Range(1, 4096))},
        {"--seed", "Random seed (default: film.seed)",
         value(&r.seed, CLI::Range(int64_t(0), INT64_MAX))},
        {"--turntable",
         "Render frames 1 to N, the camera orbiting "
         "about its up axis through look_at (a bare "
         "VDB: about the volume); output gets .####; "
         "with a shutter the orbit blurs",
         value(&r.turntable, CLI::Range(1, 100000))},
        {"--integrator",
         joinList(
             integratorInfos(),
             [](const IntegratorInfo& i) { return i.name + " (" + i.description + ")"; }, "; ") +
             "; auto (the fastest-converging method that renders all the light, "
             "chosen per scene; `mirage info` says which and why); default: the "
             "scene's [render] integrator, itself auto by default",
         value(&r.integrator)},
        {"--quality",
         "draft, preview or final: samples per pixel and, for photon, photons and "
         "k, measured on the speed-accuracy curves (docs/performance.md); a scene "
         "that states film.spp or render.photons gets them scaled by 1/4, 1 or 4, "
         "and keeps a stated render.k; --spp and --set "
         "film.spp/render.photons/render.k still win",
         value(&r.quality, CLI::IsMember({"draft", "preview", "final"}))},
    };
}

// What the EXR holds beside the beauty, and how a frame is written, resumed or skipped.
std::vector<CliOption> outputRows(RenderOptions* o) {
    FrameRequest& r = o->request;
    return {
        {"--float",
         "Write 32-bit float EXR instead of half (overrides "
         "[output] half)",
         flag(&r.floatExr)},
        {"--deep",
         "Also write a deep scanline EXR (Z, ZBack, premultiplied RGBA per stretch "
         "of volume; overrides [output] deep; docs/aovs.md)",
         value(&r.deep)},
        {"--aov",
         "Render pass beside the beauty, as EXR layer NAME (repeatable; adds to "
         "[output] aovs): emission, volume_direct, volume_indirect, surface_direct, "
         "surface_indirect, caustic, lightgroup_emission, lightgroup_<group>, "
         "alpha, depth, albedo, transmittance, variance, and the Cryptomattes "
         "crypto_volume, crypto_shape (docs/aovs.md)",
         value(&r.aovs)},
        {"-q,--quiet", "No progress output", flag(&r.quiet)},
        {"--ocio", "OCIO config file (default: $OCIO, else built-in)", value(&o->ocioConfig)},
        {"--resume",
         "Continue a killed frame from <out>.partial, bit for bit; refused if the "
         "scene or settings changed; without a partial file, render it all",
         flag(&o->resume)},
        {"--skip-existing", "Skip frames whose output EXR is complete (mirage:complete = true)",
         flag(&r.skipExisting)},
    };
}

// Motion blur, the render in passes and its stops, a region, saved photons, the memory budget.
std::vector<CliOption> renderRows(RenderOptions* o) {
    FrameRequest& r = o->request;
    return {
        {"--shutter",
         "Motion blur: shutter open for WIDTH frames centred on the frame (0.5 is "
         "a 180° shutter, 0 none); overrides [camera] shutter; volumes blur by "
         "their velocity grids (a bare VDB by its vel/v/velocity grid), keyed "
         "cameras, turntables and keyed volume transforms move within it",
         value(&r.shutter, CLI::Range(0.0, 2.0))},
        {"--motion-blur",
         "Motion blur with a 180° shutter (--shutter 0.5)",
         flag(&r.motionBlur),
         {"--shutter"}},
        {"--passes",
         "Render in passes of [render] pass_spp samples (default 4) and stop after "
         "N; with the count a --time-limit render reached (mirage:passes), the same "
         "image bit for bit",
         value(&r.passes, CLI::Range(1, kMaxSamplesPerPixel))},
        {"--time-limit",
         "Render in passes until SECONDS are spent (set-up and photon passes "
         "included): no pass starts that the last one's time says would overrun; "
         "the image is always whole passes, or, when not even the first fits, the "
         "coarse image (--coarse) that fits",
         value(&r.timeLimit, CLI::Range(1e-3, 1e9))},
        {"--noise-threshold",
         "Render in passes until the estimated relative error of the image (the "
         "race's relMSE from per-pixel variance, square-rooted; docs/cli.md) is at "
         "most E; adaptive: passes after the second sample only pixels above E",
         value(&r.noiseThreshold, CLI::Range(1e-6, 10.0))},
        {"--coarse",
         "Render only the coarse image: the frame at half its resolution with SPP "
         "samples per pixel (the path tracer where the integrator traces photons), "
         "magnified bilinearly; what a --time-limit shorter than one full pass "
         "delivers (mirage:coarse_spp), the same image bit for bit",
         value(&r.coarseSpp, CLI::Range(1, kMaxSamplesPerPixel)),
         {"--passes", "--time-limit", "--noise-threshold", "--resume"}},
        {"--region",
         "Render only pixels X0,Y0,X1,Y1 of the frame (X1, Y1 exclusive): the EXR's "
         "data window is the region, its display window the frame, and the pixels "
         "are the same bits as in a whole-frame render (mirage assemble joins "
         "regions); not with --time-limit or --noise-threshold, whose stop "
         "would depend on the region",
         value(&r.region),
         {"--time-limit", "--noise-threshold", "--coarse"}},
        {"--photons-file",
         "Render with the photon pass saved by mirage photons for this frame "
         "($F4, $F or #### take the frame) instead of tracing it; refused when "
         "made from another scene, frame or settings",
         value(&r.photonsFile)},
        {"--max-memory",
         "Fail early when the frame's estimated memory exceeds SIZE (4G, 512M, "
         "1.5G, 64k or bytes; binary multiples)",
         value(&o->maxMemory)},
    };
}

}  // namespace

std::vector<CliOption> renderOptionRows(RenderOptions* o) {
    std::vector<CliOption> table;
    for (auto rows : {inputRows, samplingRows, outputRows, renderRows})
        for (CliOption& row : rows(o)) table.push_back(std::move(row));
    return table;
}

Command addRenderCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    auto* render = app.add_subcommand("render", "Render a scene file (.toml) or a bare VDB");
    addOptions(*render, renderOptionRows(o.get()));
    return {render, [o] { return runRender(*o); }};
}

}  // namespace mirage
