// `mirage info`: what a VDB file holds, or what a scene loads and which physics it switches on.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "core/text.h"
#include "film/color.h"
#include "film/cryptomatte.h"
#include "scene/scene_info.h"

namespace mirage {

namespace {

void printGrids(const std::string& file, const VdbFileInfo& info) {
    std::printf("  %s: %s file version %s, %zu grid(s)\n", file.c_str(), info.format.c_str(),
                info.fileVersion.c_str(), info.grids.size());
    for (size_t i = 0; i < info.grids.size(); ++i) {
        const GridInfo& g = info.grids[i];
        std::printf("    [%zu] %s  type %s, class %s, compression %s\n", i,
                    g.name.empty() ? "(unnamed)" : ("'" + g.name + "'").c_str(),
                    g.valueType.c_str(), g.gridClass.c_str(), g.compression.c_str());
        std::printf(
            "        voxel size (%g, %g, %g) m, index bbox [%lld %lld %lld]..[%lld %lld %lld]\n",
            g.voxelSize.x, g.voxelSize.y, g.voxelSize.z, (long long)g.indexMin[0],
            (long long)g.indexMin[1], (long long)g.indexMin[2], (long long)g.indexMax[0],
            (long long)g.indexMax[1], (long long)g.indexMax[2]);
        std::printf("        world bounds (%g, %g, %g)..(%g, %g, %g) m\n", g.objectBounds.lo.x,
                    g.objectBounds.lo.y, g.objectBounds.lo.z, g.objectBounds.hi.x,
                    g.objectBounds.hi.y, g.objectBounds.hi.z);
        std::printf("        active voxels %llu, memory %s\n", (unsigned long long)g.activeVoxels,
                    formatBytes(g.memoryBytes).c_str());
        std::printf("        transform %s\n", g.transform.c_str());
    }
}

// One row per loaded grid: its tree's bytes at each precision ([[volume]] precision), exact from
// its leaf count (fpn at its widest, 16 bits).
void printPrecisionTable(const std::vector<SlotInfo>& slots) {
    if (slots.empty()) return;
    std::printf("    %-20s %7s", "grid bytes at", "leaves");
    for (GridPrecision p : kAllPrecisions)
        std::printf(" %11s", p == GridPrecision::FpN ? "fpn (max)" : precisionName(p));
    std::printf("\n");
    for (const SlotInfo& g : slots) {
        std::printf("    %-20s %7llu", ("'" + g.grid + "'").c_str(), (unsigned long long)g.leaves);
        for (GridPrecision p : kAllPrecisions)
            std::printf(" %11s",  // 0: unknown (from an fpn grid, whose leaves vary)
                        g.bytesAt[size_t(p)] ? formatBytes(g.bytesAt[size_t(p)]).c_str() : "-");
        std::printf("\n");
    }
}

// The grids bound to the shader's slots, the expressions, and the grids left unloaded.
void printGridUse(const VolumeInfo& v) {
    for (const SlotInfo& g : v.slots) {
        // The dense copy's size, or why lookups go through the tree (volume/dense_block.h).
        std::string dense = "dense copy " + formatBytes(g.denseBytes);
        if (!g.activeVoxels)
            dense = "empty";
        else if (!g.denseBytes)
            dense = g.precision != GridPrecision::Float ? "no dense copy (quantised)"
                                                        : "no dense copy (over its memory budget)";
        std::printf(
            "    slot '%s' ← grid '%s': %llu active voxels, NanoVDB %s at precision %s "
            "(%s), %s, max %g\n",
            g.slot.c_str(), g.grid.c_str(), (unsigned long long)g.activeVoxels,
            formatBytes(g.treeBytes).c_str(), precisionName(g.precision), g.precisionWhy.c_str(),
            dense.c_str(), g.maxValue);
    }
    printPrecisionTable(v.slots);
    for (const ExpressionRecord& e : v.expressions)
        std::printf(
            "    expression (%s, %s): %s; active voxels only; OpenVDB AX compile + "
            "run %.3f s\n      %s\n",
            e.origin.c_str(), e.expression.where.str().c_str(), describeAccess(e.access).c_str(),
            e.seconds, boundedMessage(e.expression.code, 200).c_str());
    for (const auto& u : v.unusedGrids)
        std::printf("    grid '%s' is read by no shader slot or expression: not loaded\n",
                    u.c_str());
}

// Velocity and keyed motion, the coefficients' path, emission, bounds and majorant.
void printVolumePhysics(const VolumeInfo& v) {
    if (!v.file.empty()) {
        std::printf("    velocity: %s\n", v.velocity.c_str());
        if (v.moving)
            std::printf(
                "    motion blur: lookups advected by up to %g m within the shutter; "
                "majorant dilated by it\n",
                v.blurRadius);
    }
    if (v.transformMoves)
        std::printf(
            "    transform keyed: the volume moves rigidly within the shutter "
            "(each path sees it where its time places it)\n");
    std::printf("    coefficients: %s\n",
                v.greyPath ? "grey path (every σ wavelength-independent, none fluoresces)"
                           : "spectral path (σ evaluated at each path's 4 wavelengths)");
    if (const std::optional<EmissionInfo>& e = v.emission)
        std::printf(
            "    emission: intensity %g, %zu emitting voxels above %g K, %.4g W over "
            "360–830 nm (the photon pass emits ∝ this)\n",
            e->intensity, e->voxels, e->minTemperature, e->power);
    const Bounds3& b = v.worldBounds;
    std::printf(
        "    world bounds (%g, %g, %g)..(%g, %g, %g) m, majorant %dx%dx%d cells, "
        "max σt %g 1/m\n",
        b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, v.majorantCells[0], v.majorantCells[1],
        v.majorantCells[2], v.maxSigmaT);
}

void printVolume(const VolumeInfo& v) {
    if (v.file.empty())
        std::printf("  homogeneous box (no grids)\n");
    else if (!v.vdb)
        std::printf("  %s (NanoVDB file)\n", v.file.c_str());
    else
        printGrids(v.file, *v.vdb);
    std::printf("  shader '%s' (%s), density_scale %g\n", v.shader.c_str(), v.shaderSource.c_str(),
                v.densityScale);
    for (const std::string& n : v.notes) std::printf("    %s\n", n.c_str());
    printGridUse(v);
    printVolumePhysics(v);
}

// The lights, the camera and its motion, the shutter.
void printLightsAndCamera(const SceneInfo& info) {
    std::printf("lights:\n");
    for (const LightInfo& l : info.lights)
        std::printf("  %s%s\n", l.description.c_str(),
                    l.group.empty() ? "" : ("; light group '" + l.group + "'").c_str());
    if (info.lights.empty()) std::printf("  (none)\n");
    const CameraDesc& c = info.camera;
    std::printf("camera: position (%g, %g, %g), look_at (%g, %g, %g), fov %g°\n", c.position.x,
                c.position.y, c.position.z, c.lookAt.x, c.lookAt.y, c.lookAt.z, c.fovDeg);
    if (c.keys.size() > 1 || c.orbitDegreesPerSecond != 0.f)
        std::printf("camera motion: %zu key(s)%s; %s\n", c.keys.size(),
                    c.orbitDegreesPerSecond != 0.f ? ", turntable" : "",
                    c.moves() ? "the camera moves within the shutter (camera motion blur)"
                              : "still within the closed shutter");
    if (c.motionBlur())
        std::printf("shutter: [%g, %g] frames at %g fps ([%g, %g] s): motion blur\n",
                    info.shutter.open, info.shutter.close, info.fps, double(c.shutterOpen),
                    double(c.shutterClose));
    else
        std::printf("shutter: closed (no motion blur; [camera] shutter or --shutter opens it)\n");
}

// The film, its samples (in passes, a photon map each with the photon integrator), the
// integrator and why, and the colour management.
void printFilm(const SceneInfo& info) {
    const RenderSettings& film = info.film;
    const std::string samples = info.passes.maxPasses > 0
                                    ? std::to_string(info.passes.maxPasses) + " passes of " +
                                          std::to_string(info.passes.sppPerPass) + " spp" +
                                          (info.photonMapPerPass ? " (a photon map each)" : "")
                                    : std::to_string(film.spp) + " spp";
    std::printf("film: %dx%d, %s, tile %d, seed %llu; integrator '%s' (%s); colour: %s (%s)\n",
                film.width, film.height, samples.c_str(), film.tileSize,
                (unsigned long long)film.seed, info.integrator.c_str(),
                info.integratorDescription.c_str(), info.workingSpace.c_str(),
                info.ocioConfig.c_str());
    std::printf("integrator: %s\n", info.integratorWhy.empty()
                                        ? "named by [render] integrator or --set"
                                        : info.integratorWhy.c_str());
    if (info.finalGather > 0)
        std::printf(
            "final gather: on, %d rays at the first diffuse surface ([render] "
            "final_gather)\n",
            info.finalGather);
    else if (info.finalGather == 0)
        std::printf(
            "final gather: off, indirect light read straight from the global photon map "
            "([render] final_gather = 0)\n");
    if (!info.photons.empty()) std::printf("photons: %s\n", info.photons.c_str());
}

// What the render writes beside the beauty: the passes and light groups, holdouts and deep
// output (docs/aovs.md). A scene pays only for what it asks for, so each says whether it is on.
void printOutput(const OutputInfo& out) {
    std::printf("output: %s (%s, %s)\n", out.path.c_str(), out.halfFloat ? "half float" : "float",
                out.multipart ? "one part per pass" : "one part");
    std::printf("  passes: %s\n", out.passes.empty()
                                      ? "none (the beauty alone; [output] aovs or --aov adds them)"
                                      : joinList(out.passes).c_str());
    if (!out.lightGroups.empty())
        std::printf("  light groups: %s, and emission (lightgroup_*)\n",
                    joinList(out.lightGroups).c_str());
    for (const CryptomatteInfo& c : out.cryptomattes)
        std::printf("  cryptomatte: layers %s00–%02d, %d ranks, of the %ss %s\n", c.pass.c_str(),
                    kCryptomatteRanks / 2 - 1, kCryptomatteRanks, c.kind.c_str(),
                    joinList(c.objects).c_str());
    std::printf("  holdouts: %s\n", out.holdouts.empty() ? "none" : joinList(out.holdouts).c_str());
    if (out.deep.path.empty())
        std::printf("  deep: off ([output] deep or --deep writes a deep EXR)\n");
    else
        std::printf("  deep: %s (merged within alpha %g, colour %g)\n", out.deep.path.c_str(),
                    double(out.deep.alphaTolerance), double(out.deep.colorTolerance));
}

void printSceneInfo(const std::string& input, const SceneInfo& info) {
    std::printf("%s\n", input.c_str());
    std::printf("volumes:\n");
    for (const VolumeInfo& v : info.volumes) printVolume(v);
    printLightsAndCamera(info);
    printFilm(info);
    printOutput(info.output);
    std::printf("physics:\n");
    for (const auto& t : info.physics)
        std::printf("  [%s] %-22s %s\n", t.active ? "on " : "off", t.name.c_str(), t.why.c_str());
}

// A bare volume file from its metadata and topology: its grids, and their leaves and bytes at
// each precision; its voxels are not read (a 10⁹-voxel cache in a second, not minutes).
void printVolumeFileInfo(const std::string& input, const VolumeFileInfo& info) {
    std::printf("%s\n", input.c_str());
    printGrids(info.file, info.vdb);
    printPrecisionTable(info.grids);
    std::printf(
        "voxels: not read (the file's metadata and topology only); --load loads the file as "
        "`mirage render` does and describes what it becomes: shader, binding, physics\n");
}

}  // namespace

int runInfo(const InfoOptions& o) {
    // --set and the shutter describe the scene a bare file becomes: they load it too.
    const bool asScene = o.load || !o.overrides.empty() || o.shutter >= 0 || o.motionBlur;
    if (isVolumeFile(o.input) && !asScene) {
        printVolumeFileInfo(o.input, describeVolumeFile(o.input, o.frame));
        return 0;
    }
    ColorPipeline color(o.ocioConfig);
    LoadOptions load{o.frame, o.overrides};
    const double shutterWidth = o.motionBlur ? 0.5 : o.shutter;
    if (shutterWidth >= 0) load.shutter = ShutterFrames{-0.5 * shutterWidth, 0.5 * shutterWidth};
    const Scene scene = loadScene(o.input, load, color);
    printSceneInfo(o.input, describeScene(scene, color));
    return 0;
}

Command addInfoCommand(CLI::App& app) {
    auto o = std::make_shared<InfoOptions>();
    auto* info = app.add_subcommand("info", "Describe a scene or a VDB file");
    info->add_option("input", o->input, "Scene .toml or .vdb/.nvdb")->required();
    info->add_option("--set", o->overrides, "Override scene values: key.path=value …")->take_all();
    info->add_option("--ocio", o->ocioConfig, "OCIO config file (default: $OCIO, else built-in)");
    info->add_option("--frame", o->frame,
                     "Frame number for $F/#### patterns and keyed motion (default 1)");
    info->add_option(
        "--shutter", o->shutter,
        "Describe the scene with a shutter open for WIDTH frames, as render --shutter");
    info->add_flag("--motion-blur", o->motionBlur, "The same with a 180° shutter (--shutter 0.5)")
        ->excludes("--shutter");
    info->add_flag("--load", o->load,
                   "A bare .vdb/.nvdb: load it as render does and describe the scene it becomes "
                   "(without: its metadata and topology, no voxel read)");
    return {info, [o] { return runInfo(*o); }};
}

}  // namespace mirage
