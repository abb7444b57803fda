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
                       "Output EXR (frame patterns $F4 or #### allowed); default: the scene's");
    render->add_option("--preview", ro.preview, "Also write an sRGB preview (PNG/JPEG)");
    render->add_option("--frame", ro.frame, "Frame number substituted into $F patterns");
    render->add_option("--frames", ro.frames, "Frame range A-B (inclusive)")->excludes("--frame");
    render->add_option("--set", ro.overrides, "Override a scene value: key.path=value")
        ->take_all();
    render->add_option("--resolution", ro.resolution, "Image size WxH");
    render->add_option("--spp", ro.spp, "Samples per pixel")->check(CLI::Range(1, 1 << 20));
    render->add_option("--threads", ro.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    render->add_option("--seed", ro.seed, "Random seed")->check(CLI::Range(int64_t(0), INT64_MAX));
    render->add_option("--turntable", ro.turntable, "Render N frames orbiting the volume")
        ->check(CLI::Range(1, 100000));
    render->add_option("--integrator", ro.integrator,
                       "single (single scattering + emission) or volpath (reference path tracer)");
    render->add_option("--quality", ro.quality,
                       "Preset samples/photons/k measured on the speed-accuracy curves")
        ->check(CLI::IsMember({"draft", "preview", "final"}));
    render->add_flag("--float", ro.floatExr, "Write 32-bit float EXR instead of half");
    render->add_flag("-q,--quiet", ro.quiet, "No progress output");
    render->add_option("--ocio", ro.ocioConfig, "OCIO config (default: $OCIO, else built-in)");
    render->add_flag("--resume", ro.resume,
                     "Continue a killed frame from <out>.partial (same scene and settings)");
    render->add_flag("--skip-existing", ro.skipExisting,
                     "Skip frames whose output EXR is complete (mirage:complete = true)");
    render->add_option("--max-memory", ro.maxMemory,
                       "Fail early when the frame's estimated memory exceeds SIZE (4G, 512M)");

    InfoOptions io;
    auto* info = app.add_subcommand("info", "Describe a scene or a VDB file");
    info->add_option("input", io.input, "Scene .toml or .vdb/.nvdb")->required();
    info->add_option("--set", io.overrides, "Override a scene value: key.path=value")->take_all();
    info->add_option("--ocio", io.ocioConfig, "OCIO config (default: $OCIO, else built-in)");

    AssetOptions ao;
    auto* asset = app.add_subcommand("make-asset", "Write a procedural VDB cache");
    asset->add_option("kind", ao.kind, "smoke | fire | fog-sphere | ocean")->required();
    asset->add_option("-o,--output", ao.output, "Output .vdb")->required();
    asset->add_option("--resolution", ao.resolution, "Voxels along the tallest axis")
        ->check(CLI::Range(4, 2048));
    asset->add_option("--seed", ao.seed, "Noise seed");

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
                   "Flat 380–780 nm source: reflectance/transmittance per 5 nm bin");
    slab->add_option("--g", so.g, "Henyey–Greenstein asymmetry")
        ->check(CLI::Range(-0.9999, 0.9999));
    slab->add_option("--n", so.n, "Refractive index of the slab")->check(CLI::Range(0.01, 100.0));
    slab->add_option("--n-outside", so.nOutside, "Refractive index around the slab (default 1)")
        ->check(CLI::Range(0.01, 100.0));
    slab->add_option("--incidence", so.incidence, "normal (collimated) or diffuse (Lambertian)")
        ->check(CLI::IsMember({"normal", "diffuse"}));
    slab->add_option("--photons", so.photons, "Photons to trace")
        ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
    slab->add_option("--seed", so.seed, "Random seed");
    slab->add_option("--max-events", so.maxEvents,
                     "Cap on scatterings + internal reflections per photon (capped: reported)")
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
    tradeoff->add_option("--set", to.overrides, "Override a scene value: key.path=value")
        ->take_all();
    tradeoff->add_option("--resolution", to.resolution, "Image size WxH");
    tradeoff->add_option("--spp", to.spp, "Samples per pixel unless varied")
        ->check(CLI::Range(1, 1 << 20));
    tradeoff->add_option("--integrator", to.integrator, "single, volpath or photon unless varied");
    tradeoff->add_option("--threads", to.threads, "Worker threads (default: all cores)")
        ->check(CLI::Range(1, 4096));
    tradeoff->add_option("--seed", to.seed, "Random seed")->check(CLI::Range(int64_t(0), INT64_MAX));
    tradeoff->add_option("--repeats", to.repeats, "Renders per setting; the median time is kept")
        ->check(CLI::Range(1, 1000));
    tradeoff->add_option("-o,--output", to.prefix,
                         "Prefix of the output files <prefix>tradeoff.csv, .png, reference.exr");
    tradeoff->add_option("--ocio", to.ocioConfig, "OCIO config (default: $OCIO, else built-in)");
    tradeoff->add_flag("-q,--quiet", to.quiet, "No progress output");

    RaypathOptions rp;
    auto* raypath = app.add_subcommand(
        "raypath", "Trace one curved light path through a refractive-index profile");
    raypath->add_option("--profile", rp.profile, "linear (n = n0 + k·y) or atmosphere")
        ->check(CLI::IsMember({"linear", "atmosphere"}));
    raypath->add_option("--n0", rp.n0, "linear: index at y = 0")->check(CLI::PositiveNumber);
    raypath->add_option("--k", rp.k, "linear: dn/dy in 1/m");
    raypath->add_option("--origin", rp.origin, "Start point x,y,z in metres");
    raypath->add_option("--direction", rp.direction, "Start direction x,y,z (normalised)");
    raypath->add_option("--length", rp.length, "Arc length to trace, m")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--tolerance", rp.tolerance, "rk45: error tolerance per step")
        ->check(CLI::Range(1e-16, 1.0));
    raypath->add_option("--method", rp.method, "rk45 (Dormand-Prince 5(4)) or euler")
        ->check(CLI::IsMember({"rk45", "euler"}));
    raypath->add_option("--step", rp.step, "euler: fixed step, m")->check(CLI::PositiveNumber);
    raypath->add_option("--max-step", rp.maxStep, "rk45: largest step, m (default unlimited)")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--max-steps", rp.maxSteps, "Hard cap on steps (reached: reported)")
        ->check(CLI::PositiveNumber);
    raypath->add_option("--wavelength", rp.wavelength, "Wavelength, nm")
        ->check(CLI::Range(360.0, 830.0));
    raypath->add_option("--inversion", rp.inversions,
                        "atmosphere: a layer BASE,TOP,DT[,BLEND] (m, m, K, m) warmer by DT "
                        "between BASE and TOP, edges blended over BLEND (default 1 m); "
                        "repeatable");
    raypath->add_flag("--json", rp.json, "Print the result as JSON");

    // Command-line syntax errors exit 2 (README "Input rules"); CLI11's own codes (105 for a
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
