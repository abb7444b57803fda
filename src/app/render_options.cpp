// The options of `mirage render` and their help text (docs/cli.md is the long form); the command
// itself is runRender (render_command.cpp).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>

#include "app/commands.h"
#include "core/text.h"
#include "render/integrator.h"
#include "render/passes.h"

namespace mirage {

Command addRenderCommand(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    auto* render = app.add_subcommand("render", "Render a scene file (.toml) or a bare VDB");
    render->add_option("input", o->request.input, "Scene .toml, or a .vdb/.nvdb for a quick look")
        ->required();
    render->add_option("-o,--output", o->request.output,
                       "Output EXR; $F4, $F or #### take the frame (a sequence without a pattern "
                       "gets .#### before the extension); default: the scene's [output] path");
    render->add_option("--preview", o->request.preview,
                       "Also write a display preview (PNG/JPEG) through "
                       "the scene's [output] display/view (default "
                       "sRGB, Standard); default: the scene's preview");
    render->add_option("--frame", o->frame,
                       "Frame number for $F/#### patterns and turntables "
                       "(default 1)");
    render
        ->add_option("--frames", o->frames,
                     "Render frames A to B (inclusive), e.g. 1-24; A-BxS every S-th "
                     "frame, e.g. 1-48x2")
        ->excludes("--frame");
    render
        ->add_option("--set", o->request.overrides,
                     "Override scene values before loading: "
                     "key.path=value …, e.g. film.spp=64 "
                     "volume.0.density_scale=2 (a bare VDB: film.*, "
                     "render.*, output.* only)")
        ->take_all();
    render->add_option("--resolution", o->request.resolution,
                       "Image size WxH (overrides "
                       "film.resolution; a bare VDB's camera "
                       "reframes)");
    render
        ->add_option("--spp", o->request.spp,
                     "Samples per pixel (overrides film.spp and --quality)")
        ->check(CLI::Range(1, 1 << 20));
    render->add_option("--threads", o->threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    render->add_option("--seed", o->request.seed, "Random seed (default: film.seed)")
        ->check(CLI::Range(int64_t(0), INT64_MAX));
    render
        ->add_option("--turntable", o->request.turntable,
                     "Render frames 1 to N, the camera orbiting "
                     "about its up axis through look_at (a bare "
                     "VDB: about the volume); output gets .####; "
                     "with a shutter the orbit blurs")
        ->check(CLI::Range(1, 100000));
    render->add_option(
        "--integrator", o->request.integrator,
        joinList(
            integratorInfos(),
            [](const IntegratorInfo& i) { return i.name + " (" + i.description + ")"; }, "; ") +
            "; auto (the fastest-converging method that renders all the light, "
            "chosen per scene; `mirage info` says which and why); default: the "
            "scene's [render] integrator, itself auto by default");
    render
        ->add_option("--quality", o->request.quality,
                     "draft, preview or final: samples per pixel and, for photon, photons and "
                     "k, measured on the speed-accuracy curves (docs/performance.md); a scene "
                     "that states film.spp or render.photons gets them scaled by 1/4, 1 or 4, "
                     "and keeps a stated render.k; --spp and --set "
                     "film.spp/render.photons/render.k still win")
        ->check(CLI::IsMember({"draft", "preview", "final"}));
    render->add_flag("--float", o->request.floatExr,
                     "Write 32-bit float EXR instead of half (overrides "
                     "[output] half)");
    render->add_option("--deep", o->request.deep,
                       "Also write a deep scanline EXR (Z, ZBack, premultiplied RGBA per stretch "
                       "of volume; overrides [output] deep; docs/aovs.md)");
    render->add_option("--aov", o->request.aovs,
                       "Render pass beside the beauty, as EXR layer NAME (repeatable; adds to "
                       "[output] aovs): emission, volume_direct, volume_indirect, surface_direct, "
                       "surface_indirect, caustic, lightgroup_emission, lightgroup_<group>, "
                       "alpha, depth, albedo, transmittance, variance, and the Cryptomattes "
                       "crypto_volume, crypto_shape (docs/aovs.md)");
    render->add_flag("-q,--quiet", o->request.quiet, "No progress output");
    render->add_option("--ocio", o->ocioConfig, "OCIO config file (default: $OCIO, else built-in)");
    render->add_flag("--resume", o->resume,
                     "Continue a killed frame from <out>.partial, bit for bit; refused if the "
                     "scene or settings changed; without a partial file, render it all");
    render->add_flag("--skip-existing", o->request.skipExisting,
                     "Skip frames whose output EXR is complete (mirage:complete = true)");
    render
        ->add_option("--shutter", o->request.shutter,
                     "Motion blur: shutter open for WIDTH frames centred on the frame (0.5 is "
                     "a 180° shutter, 0 none); overrides [camera] shutter; volumes blur by "
                     "their velocity grids (a bare VDB by its vel/v/velocity grid), keyed "
                     "cameras, turntables and keyed volume transforms move within it")
        ->check(CLI::Range(0.0, 2.0));
    render
        ->add_flag("--motion-blur", o->request.motionBlur,
                   "Motion blur with a 180° shutter (--shutter 0.5)")
        ->excludes("--shutter");
    render
        ->add_option("--passes", o->request.passes,
                     "Render in passes of [render] pass_spp samples (default 4) and stop after "
                     "N; with the count a --time-limit render reached (mirage:passes), the same "
                     "image bit for bit")
        ->check(CLI::Range(1, kMaxSamplesPerPixel));
    render
        ->add_option("--time-limit", o->request.timeLimit,
                     "Render in passes until SECONDS are spent (set-up and photon passes "
                     "included): no pass starts that the last one's time says would overrun; "
                     "the image is always whole passes, or, when not even the first fits, the "
                     "coarse image (--coarse) that fits")
        ->check(CLI::Range(1e-3, 1e9));
    render
        ->add_option("--noise-threshold", o->request.noiseThreshold,
                     "Render in passes until the estimated relative error of the image (the "
                     "race's relMSE from per-pixel variance, square-rooted; docs/cli.md) is at "
                     "most E; adaptive: passes after the second sample only pixels above E")
        ->check(CLI::Range(1e-6, 10.0));
    render
        ->add_option("--coarse", o->request.coarseSpp,
                     "Render only the coarse image: the frame at half its resolution with SPP "
                     "samples per pixel (the path tracer where the integrator traces photons), "
                     "magnified bilinearly; what a --time-limit shorter than one full pass "
                     "delivers (mirage:coarse_spp), the same image bit for bit")
        ->check(CLI::Range(1, kMaxSamplesPerPixel))
        ->excludes("--passes")
        ->excludes("--time-limit")
        ->excludes("--noise-threshold")
        ->excludes("--resume");
    render
        ->add_option("--region", o->request.region,
                     "Render only pixels X0,Y0,X1,Y1 of the frame (X1, Y1 exclusive): the EXR's "
                     "data window is the region, its display window the frame, and the pixels "
                     "are the same bits as in a whole-frame render (mirage assemble joins "
                     "regions); not with --time-limit or --noise-threshold, whose stop "
                     "would depend on the region")
        ->excludes("--time-limit")
        ->excludes("--noise-threshold")
        ->excludes("--coarse");
    render->add_option("--photons-file", o->request.photonsFile,
                       "Render with the photon pass saved by mirage photons for this frame "
                       "($F4, $F or #### take the frame) instead of tracing it; refused when "
                       "made from another scene, frame or settings");
    render->add_option("--max-memory", o->maxMemory,
                       "Fail early when the frame's estimated memory exceeds SIZE (4G, 512M, "
                       "1.5G, 64k or bytes; binary multiples)");
    return {render, [o] { return runRender(*o); }};
}

}  // namespace mirage
