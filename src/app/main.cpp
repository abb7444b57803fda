// mirage — command-line entry point. One try/catch: user mistakes (MirageError) print one
// message and exit 1; command-line syntax errors exit 2 (CLI11's convention).
#include <CLI/CLI.hpp>

#include <cstdio>

#include "app/commands.h"
#include "core/error.h"

int main(int argc, char** argv) {
    using namespace mirage;
    CLI::App app{"Mirage " MIRAGE_VERSION " — spectral volume renderer for OpenVDB caches"};
    app.require_subcommand(1);
    app.set_version_flag("--version", MIRAGE_VERSION);

    RenderOptions ro;
    auto* render = app.add_subcommand("render", "Render a scene file (.toml) or a bare VDB");
    render->add_option("input", ro.input, "Scene .toml, or a .vdb/.nvdb for a quick look")
        ->required();
    render->add_option("-o,--output", ro.output,
                       "Output EXR; $F4, $F or #### take the frame (a sequence without a pattern "
                       "gets .#### before the extension); default: the scene's [output] path");
    render->add_option("--preview", ro.preview,
                       "Also write a display preview (PNG/JPEG) through the scene's [output] "
                       "display/view (default sRGB, Standard); default: the scene's preview");
    render->add_option("--frame", ro.frame,
                       "Frame number for $F/#### patterns and turntables (default 1)");
    render->add_option("--frames", ro.frames, "Render frames A to B (inclusive), e.g. 1-24")
        ->excludes("--frame");
    render
        ->add_option("--set", ro.overrides,
                     "Override scene values before loading: key.path=value …, e.g. "
                     "film.spp=64 volume.0.density_scale=2 (a bare VDB: film.*, render.*, "
                     "output.* only)")
        ->take_all();
    render->add_option("--resolution", ro.resolution,
                       "Image size WxH (overrides film.resolution; a bare VDB's camera "
                       "reframes)");
    render->add_option("--spp", ro.spp, "Samples per pixel (overrides film.spp and --quality)")
        ->check(CLI::Range(1, 1 << 20));
    render->add_option("--threads", ro.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    render->add_option("--seed", ro.seed, "Random seed (default: film.seed)")
        ->check(CLI::Range(int64_t(0), INT64_MAX));
    render
        ->add_option("--turntable", ro.turntable,
                     "Render frames 1 to N, the camera orbiting about its up axis through "
                     "look_at (a bare VDB: about the volume); output gets .####")
        ->check(CLI::Range(1, 100000));
    render->add_option("--integrator", ro.integrator,
                       "single (single scattering + emission), volpath (reference path tracer) "
                       "or photon (volume photon mapping); default: the scene's [render] "
                       "integrator");
    render
        ->add_option("--quality", ro.quality,
                     "draft, preview or final: samples per pixel and, for photon, photons and k, "
                     "measured on the speed-accuracy curves (docs/performance.md); --spp and "
                     "--set film.spp/render.photons/render.k still win")
        ->check(CLI::IsMember({"draft", "preview", "final"}));
    render->add_flag("--float", ro.floatExr,
                     "Write 32-bit float EXR instead of half (overrides [output] half)");
    render->add_flag("-q,--quiet", ro.quiet, "No progress output");
    render->add_option("--ocio", ro.ocioConfig, "OCIO config file (default: $OCIO, else built-in)");
    render->add_flag("--resume", ro.resume,
                     "Continue a killed frame from <out>.partial, bit for bit; refused if the "
                     "scene or settings changed; without a partial file, render it all");
    render->add_flag("--skip-existing", ro.skipExisting,
                     "Skip frames whose output EXR is complete (mirage:complete = true)");
    render
        ->add_option("--shutter", ro.shutter,
                     "Velocity motion blur: shutter open for WIDTH frames centred on the frame "
                     "(0.5 is a 180° shutter, 0 none); overrides [camera] shutter, and works "
                     "for a bare VDB with a vel/v/velocity grid")
        ->check(CLI::Range(0.0, 2.0));
    render->add_flag("--motion-blur", ro.motionBlur,
                     "Velocity motion blur with a 180° shutter (--shutter 0.5)")
        ->excludes("--shutter");
    render->add_option("--max-memory", ro.maxMemory,
                       "Fail early when the frame's estimated memory exceeds SIZE (4G, 512M, 1.5G, "
                       "64k or bytes; binary multiples)");

    InfoOptions io;
    auto* info = app.add_subcommand("info", "Describe a scene or a VDB file");
    info->add_option("input", io.input, "Scene .toml or .vdb/.nvdb")->required();
    info->add_option("--set", io.overrides, "Override scene values: key.path=value …")->take_all();
    info->add_option("--ocio", io.ocioConfig, "OCIO config file (default: $OCIO, else built-in)");

    AssetOptions ao;
    auto* asset = app.add_subcommand("make-asset", "Write a procedural VDB cache");
    asset->add_option("kind", ao.kind, "smoke | fire | fog-sphere | ocean")->required();
    asset->add_option("-o,--output", ao.output, "Output .vdb (written atomically)")->required();
    asset
        ->add_option("--resolution", ao.resolution,
                     "Voxels along the 2 m height, 8 to 1024 (default 64)")
        ->check(CLI::Range(4, 2048));
    asset->add_option("--seed", ao.seed, "Noise seed (default 1; fog-sphere ignores it)");

    SlabOptions so;
    auto* slab = app.add_subcommand(
        "slab", "Reflectance and transmittance of a plane-parallel slab, by photon tracing");
    slab->add_option("--albedo", so.albedo, "Single-scattering albedo σs/σt (without --shader)")
        ->check(CLI::Range(0.0, 1.0));
    slab->add_option("--tau", so.tau,
                     "Optical thickness σt·d; inf for a semi-infinite slab (without --shader)");
    slab->add_option("--shader", so.shader,
                     "Shader (name or .toml) made homogeneous, instead of --albedo/--tau/--g");
    slab->add_option("--set", so.sets,
                     "With --shader: NAME=C sets a component's concentration (e.g. "
                     "chlorophyll=5), NAME.quantum_efficiency=Γ its fluorescence")
        ->take_all();
    slab->add_option("--thickness", so.thickness,
                     "With --shader: slab thickness in metres (default: a deep column)")
        ->check(CLI::Range(1e-9, 1e9));
    slab->add_flag("--spectral", so.spectral,
                   "Flat 380–780 nm source: reflectance, transmittance and fluorescence per "
                   "5 nm bin (without it: 550 nm)");
    slab->add_option("--g", so.g, "Henyey–Greenstein asymmetry (default 0; without --shader)")
        ->check(CLI::Range(-0.9999, 0.9999));
    slab->add_option("--n", so.n, "Refractive index of the slab (default 1)")
        ->check(CLI::Range(0.01, 100.0));
    slab->add_option("--n-outside", so.nOutside, "Refractive index around the slab (default 1)")
        ->check(CLI::Range(0.01, 100.0));
    slab->add_option("--incidence", so.incidence,
                     "normal (collimated, the default) or diffuse (Lambertian)")
        ->check(CLI::IsMember({"normal", "diffuse"}));
    slab->add_option("--photons", so.photons, "Photons to trace (default 1000000)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
    slab->add_option("--seed", so.seed, "Random seed (default 0)");
    slab->add_option("--max-events", so.maxEvents,
                     "Cap on scatterings + internal reflections per photon (default 1000000; "
                     "capped photons are reported)")
        ->check(CLI::Range(int64_t(1), int64_t(1) << 40));
    slab->add_option("--threads", so.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    slab->add_flag("--json", so.json, "Print the result as JSON");
    slab->add_flag("-q,--quiet", so.quiet, "No progress output");

    TradeoffOptions to;
    auto* tradeoff = app.add_subcommand(
        "tradeoff", "Error against a reference versus render time over a sweep of settings");
    tradeoff->add_option("input", to.input, "Scene .toml")->required();
    tradeoff->add_option("--vary", to.vary,
                         "NAME=v1,v2,…: photons, estimate, k, max_radius, spp, integrator or "
                         "any dotted scene key; several form the Cartesian product")
        ->required();
    tradeoff->add_option("--reference", to.reference,
                         "Reference EXR (default: render one with volpath, write "
                         "<prefix>reference.exr)");
    tradeoff->add_option("--reference-spp", to.referenceSpp,
                         "Samples per pixel of a rendered reference (default: 4x the sweep's "
                         "highest, at least 256)")
        ->check(CLI::Range(1, 1 << 20));
    tradeoff
        ->add_option("--set", to.overrides,
                     "Override scene values before the varied keys: key.path=value …")
        ->take_all();
    tradeoff->add_option("--resolution", to.resolution,
                         "Image size WxH (overrides film.resolution)");
    tradeoff->add_option("--spp", to.spp, "Samples per pixel unless varied")
        ->check(CLI::Range(1, 1 << 20));
    tradeoff->add_option("--integrator", to.integrator,
                         "single, volpath or photon unless varied (default: the scene's)");
    tradeoff->add_option("--threads", to.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    tradeoff->add_option("--seed", to.seed, "Random seed (default: film.seed)")
        ->check(CLI::Range(int64_t(0), INT64_MAX));
    tradeoff
        ->add_option("--repeats", to.repeats,
                     "Renders per setting; the median time is kept (default 1)")
        ->check(CLI::Range(1, 1000));
    tradeoff->add_option("-o,--output", to.prefix,
                         "Prefix of the output files <prefix>tradeoff.csv, .png, reference.exr");
    tradeoff->add_option("--ocio", to.ocioConfig,
                         "OCIO config file (default: $OCIO, else built-in)");
    tradeoff->add_flag("-q,--quiet", to.quiet, "No progress output");

    RaypathOptions rp;
    auto* raypath = app.add_subcommand(
        "raypath", "Trace one curved light path through a refractive-index profile");
    raypath
        ->add_option("--profile", rp.profile,
                     "linear (n = n0 + k·y, the default) or atmosphere (US Standard "
                     "Atmosphere 1976, y = height above sea level)")
        ->check(CLI::IsMember({"linear", "atmosphere"}));
    raypath->add_option("--n0", rp.n0, "linear: index at y = 0 (default 1)")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--k", rp.k, "linear: dn/dy in 1/m (default 0)");
    raypath->add_option("--origin", rp.origin, "Start point x,y,z in metres (default 0,0,0)");
    raypath->add_option("--direction", rp.direction,
                        "Start direction x,y,z, any length (default 1,0,0)");
    raypath->add_option("--length", rp.length, "Arc length to trace, m (default 1)")
        ->check(CLI::PositiveNumber);
    raypath
        ->add_option("--tolerance", rp.tolerance,
                     "rk45: largest accepted error estimate per step, absolute (default 1e-6)")
        ->check(CLI::Range(1e-16, 1.0));
    raypath
        ->add_option("--method", rp.method,
                     "rk45 (Dormand-Prince 5(4), the default) or euler (fixed step)")
        ->check(CLI::IsMember({"rk45", "euler"}));
    raypath->add_option("--step", rp.step, "euler: fixed step, m (default 0.01)")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--max-step", rp.maxStep, "rk45: largest step, m (default unlimited)")
        ->check(CLI::PositiveNumber);
    raypath
        ->add_option("--max-steps", rp.maxSteps,
                     "Cap on accepted + rejected steps (default 10000000); reaching it is an "
                     "error")
        ->check(CLI::PositiveNumber);
    raypath
        ->add_option("--wavelength", rp.wavelength,
                     "Wavelength, nm (default 550; matters for dispersive fields)")
        ->check(CLI::Range(360.0, 830.0));
    raypath->add_option("--inversion", rp.inversions,
                        "atmosphere: a layer BASE,TOP,DT[,BLEND] (m, m, K, m) warmer by DT "
                        "between BASE and TOP, edges blended over BLEND (default 1 m); "
                        "repeatable");
    raypath->add_flag("--json", rp.json, "Print the result as JSON");

    // Command-line syntax errors exit 2 (docs/cli.md); CLI11's own codes (105 for a
    // bad option value, 106 for a missing one, ...) would tell a farm wrapper nothing stable.
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : 2;
    }
    try {
        if (*render) return runRender(ro);
        if (*info) return runInfo(io);
        if (*asset) return runMakeAsset(ao);
        if (*slab) return runSlab(so);
        if (*tradeoff) return runTradeoff(to);
        if (*raypath) return runRaypath(rp);
    } catch (const MirageError& e) {
        std::fprintf(stderr, "mirage: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "mirage: error: %s\n", boundedMessage(e.what()).c_str());
        return 1;
    }
    return 0;
}
