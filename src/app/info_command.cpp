// `mirage info`: what a VDB file holds, or what a scene loads and which physics it switches on.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "core/text.h"
#include "film/color.h"
#include "film/cryptomatte.h"
#include "photon/medium_emitter.h"
#include "scene/scene.h"
#include "volume/vdb_file.h"

namespace mirage {

namespace {

void printGrids(const std::string& file) {
    if (file.size() > 5 && file.substr(file.size() - 5) == ".nvdb") {
        std::printf("  %s (NanoVDB file)\n", file.c_str());
        return;
    }
    VdbFileInfo info = inspectVdbFile(file);
    std::printf("  %s: OpenVDB file version %s, %zu grid(s)\n", file.c_str(),
                info.fileVersion.c_str(), info.grids.size());
    for (size_t i = 0; i < info.grids.size(); ++i) {
        const GridInfo& g = info.grids[i];
        std::printf("    [%zu] %s  type %s, class %s, compression %s\n", i,
                    g.name.empty() ? "(unnamed)" : ("'" + g.name + "'").c_str(),
                    g.valueType.c_str(), g.gridClass.c_str(), g.compression.c_str());
        std::printf("        voxel size (%g, %g, %g) m, index bbox [%lld %lld %lld]..[%lld %lld %lld]\n",
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

// Light `i`'s group, as the lightgroup_* passes name it ("" when no light has a group).
std::string lightGroupOf(const RenderScene& scene, size_t i) {
    if (scene.lightGroups.empty()) return "";
    return scene.lightGroupNames()[size_t(scene.lightGroupSlot(i) - 1)];
}

// What the render writes beside the beauty: the passes and light groups, holdouts and deep
// output (docs/aovs.md). A scene pays only for what it asks for, so each says whether it is on.
void printOutput(const Scene& scene) {
    const RenderSettings& s = scene.settings;
    std::printf("output: %s (%s, %s)\n", scene.output.path.c_str(),
                scene.output.halfFloat ? "half float" : "float",
                scene.output.multipart ? "one part per pass" : "one part");
    std::printf("  passes: %s\n", s.aovs.empty()
                                      ? "none (the beauty alone; [output] aovs or --aov adds them)"
                                      : joinList(s.aovs).c_str());
    if (!scene.render.lightGroups.empty())
        std::printf("  light groups: %s, and emission (lightgroup_*)\n",
                    joinList(scene.render.lightGroupNames()).c_str());
    for (const char* kind : {"volume", "shape"}) {
        const std::string pass = cryptomattePass(kind);
        if (std::find(s.aovs.begin(), s.aovs.end(), pass) == s.aovs.end()) continue;
        const CryptoObjects& o = scene.render.cryptoObjects;
        std::printf("  cryptomatte: layers %s00–%02d, %d ranks, of the %ss %s\n", pass.c_str(),
                    kCryptomatteRanks / 2 - 1, kCryptomatteRanks, kind,
                    joinList(std::string(kind) == "volume" ? o.volumes : o.shapes).c_str());
    }
    std::vector<std::string> holdouts;
    for (size_t i = 0; i < scene.render.media.size(); ++i)
        if (scene.render.holdout(i)) holdouts.push_back("volume " + std::to_string(i));
    const GeometryScene* g = scene.render.geometry.get();
    for (size_t i = 0; g && i < g->shapeCount(); ++i)
        if (g->shape(int(i)).holdout) holdouts.push_back("shape " + std::to_string(i));
    std::printf("  holdouts: %s\n", holdouts.empty() ? "none" : joinList(holdouts).c_str());
    if (s.deep.path.empty())
        std::printf("  deep: off ([output] deep or --deep writes a deep EXR)\n");
    else
        std::printf("  deep: %s (merged within alpha %g, colour %g)\n", s.deep.path.c_str(),
                    double(s.deep.alphaTolerance), double(s.deep.colorTolerance));
}

}  // namespace

int runInfo(const InfoOptions& o) {
    ColorPipeline color(o.ocioConfig);
    LoadOptions load{o.frame, o.overrides};
    const double shutterWidth = o.motionBlur ? 0.5 : o.shutter;
    if (shutterWidth >= 0) load.shutter = ShutterFrames{-0.5 * shutterWidth, 0.5 * shutterWidth};
    Scene scene = loadScene(o.input, load, color);
    std::printf("%s\n", o.input.c_str());
    std::printf("volumes:\n");
    for (size_t i = 0; i < scene.volumes.size(); ++i) {
        const VolumeRecord& v = scene.volumes[i];
        const Medium& m = *scene.render.media[i];
        if (v.file.empty())
            std::printf("  homogeneous box (no grids)\n");
        else
            printGrids(v.file);
        std::printf("  shader '%s' (%s), density_scale %g\n", v.shader.c_str(),
                    m.shader().source.c_str(), v.densityScale);
        for (const std::string& n : v.notes) std::printf("    %s\n", n.c_str());
        for (size_t b = 0; b < v.bindings.size(); ++b) {
            const FloatGrid& g = m.binding().grids()[b];
            // The dense copy's size, or why lookups go through the tree (volume/dense_block.h).
            const std::string dense = g.denseBytes() ? "dense copy " + formatBytes(g.denseBytes())
                                      : g.activeVoxels()
                                          ? std::string("no dense copy (over its memory budget)")
                                          : std::string("empty");
            std::printf("    slot '%s' ← grid '%s': %llu active voxels, NanoVDB %s, %s, max %g\n",
                        v.bindings[b].first.c_str(), v.bindings[b].second.c_str(),
                        (unsigned long long)g.activeVoxels(), formatBytes(g.treeBytes()).c_str(),
                        dense.c_str(), g.maxValue());
        }
        for (const ExpressionRecord& e : v.expressions)
            std::printf("    expression (%s, %s): %s; active voxels only; OpenVDB AX compile + "
                        "run %.3f s\n      %s\n",
                        e.origin.c_str(), e.expression.where.str().c_str(),
                        describeAccess(e.access).c_str(), e.seconds,
                        boundedMessage(e.expression.code, 200).c_str());
        for (const auto& u : v.unusedGrids)
            std::printf("    grid '%s' is read by no shader slot or expression: not loaded\n",
                        u.c_str());
        if (!v.file.empty()) {
            // Described even with the shutter closed (the render then does not load it).
            VelocityRecord velocity = v.velocity;
            if (!velocity.grid.empty() && !velocity.velocity.valid())
                velocity.velocity = loadVelocityGrid(v.file, velocity.grid);
            std::printf("    velocity: %s\n", describeVelocity(velocity).c_str());
            if (m.motion().moving())
                std::printf("    motion blur: lookups advected by up to %g m within the shutter; "
                            "majorant dilated by it\n",
                            double(m.motion().blurRadius()));
        }
        if (m.motion().transformMoves())
            std::printf(
                "    transform keyed: the volume moves rigidly within the shutter "
                "(each path sees it where its time places it)\n");
        std::printf("    coefficients: %s\n",
                    m.greyPath() ? "grey path (every σ wavelength-independent, none fluoresces)"
                                 : "spectral path (σ evaluated at each path's 4 wavelengths)");
        if (m.emissive() && !m.homogeneous()) {
            MediumEmitter emitter(m);
            std::printf("    emission: intensity %g, %zu emitting voxels above %g K, %.4g W over "
                        "360–830 nm (the photon pass emits ∝ this)\n",
                        m.shader().emission->intensity, emitter.emittingVoxels(),
                        m.shader().emission->minTemperature, emitter.tablePower());
        }
        Bounds3 b = m.worldBounds();
        std::printf("    world bounds (%g, %g, %g)..(%g, %g, %g) m, majorant %dx%dx%d cells, "
                    "max σt %g 1/m\n",
                    b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, m.majorant().res(0),
                    m.majorant().res(1), m.majorant().res(2), m.majorant().maxValue());
    }
    std::printf("lights:\n");
    for (size_t i = 0; i < scene.render.lights.size(); ++i) {
        const std::string group = lightGroupOf(scene.render, i);
        std::printf("  %s%s\n", scene.render.lights[i]->describe().c_str(),
                    group.empty() ? "" : ("; light group '" + group + "'").c_str());
    }
    if (scene.render.lights.empty()) std::printf("  (none)\n");
    const CameraDesc& c = scene.render.camera;
    std::printf("camera: position (%g, %g, %g), look_at (%g, %g, %g), fov %g°\n", c.position.x,
                c.position.y, c.position.z, c.lookAt.x, c.lookAt.y, c.lookAt.z, c.fovDeg);
    if (c.keys.size() > 1 || c.orbitDegreesPerSecond != 0.f)
        std::printf("camera motion: %zu key(s)%s; %s\n", c.keys.size(),
                    c.orbitDegreesPerSecond != 0.f ? ", turntable" : "",
                    c.moves() ? "the camera moves within the shutter (camera motion blur)"
                              : "still within the closed shutter");
    if (c.motionBlur())
        std::printf("shutter: [%g, %g] frames at %g fps ([%g, %g] s): motion blur\n",
                    scene.shutter.open, scene.shutter.close, scene.output.fps,
                    double(c.shutterOpen), double(c.shutterClose));
    else
        std::printf("shutter: closed (no motion blur; [camera] shutter or --shutter opens it)\n");
    // [render] passes: the samples come in passes, and the photon integrator makes a map per pass.
    const std::string samples =
        scene.passes.maxPasses > 0
            ? std::to_string(scene.passes.maxPasses) + " passes of " +
                  std::to_string(scene.passes.sppPerPass) + " spp" +
                  (integratorInfo(scene.integrator).photonPass ? " (a photon map each)" : "")
            : std::to_string(scene.settings.spp) + " spp";
    std::printf("film: %dx%d, %s, tile %d, seed %llu; integrator '%s' (%s); colour: %s (%s)\n",
                scene.settings.width, scene.settings.height, samples.c_str(),
                scene.settings.tileSize, (unsigned long long)scene.settings.seed,
                scene.integrator.c_str(), integratorInfo(scene.integrator).description.c_str(),
                color.workingSpace().c_str(), color.configDescription().c_str());
    std::printf("integrator: %s\n", scene.integratorWhy.empty()
                                        ? "named by [render] integrator or --set"
                                        : scene.integratorWhy.c_str());
    printOutput(scene);
    std::printf("physics:\n");
    for (const auto& t : scene.physics())
        std::printf("  [%s] %-22s %s\n", t.active ? "on " : "off", t.name.c_str(), t.why.c_str());
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
    return {info, [o] { return runInfo(*o); }};
}

}  // namespace mirage
