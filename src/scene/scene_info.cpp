// The record of a loaded scene for `mirage info` (scene_info.h).
#include "scene/scene_info.h"

#include <algorithm>

#include "core/grid_name.h"
#include "film/color.h"
#include "film/cryptomatte.h"
#include "photon/medium_emitter.h"
#include "photon/projection_map.h"

namespace mirage {

namespace {

bool isNanoVdb(const std::string& file) {
    return file.size() > 5 && file.substr(file.size() - 5) == ".nvdb";
}

// The grids bound to the shader's slots.
std::vector<SlotInfo> slotsOf(const VolumeRecord& v, const Medium& m) {
    std::vector<SlotInfo> slots;
    for (size_t b = 0; b < v.bindings.size(); ++b) {
        const FloatGrid& g = m.binding().grids()[b];
        SlotInfo slot{v.bindings[b].first, v.bindings[b].second, g.activeVoxels(),
                      g.treeBytes(),       g.denseBytes(),       g.maxValue(),
                      g.precision(),       g.leafCount(),        {},                   {}};
        for (GridPrecision p : kAllPrecisions) slot.bytesAt[size_t(p)] = g.treeBytesAt(p);
        slot.precisionWhy = v.precisionWhy;
        slots.push_back(slot);
    }
    return slots;
}

// Motion: the velocity grid (named, with why it is unloaded, when the shutter is closed: a grid
// the render does not read is not read for its description either) and how far it moves the
// lookups; a keyed transform.
void describeMotion(const VolumeRecord& v, const Medium& m, VolumeInfo* info) {
    info->transformMoves = m.motion().transformMoves();
    if (v.file.empty()) return;
    info->velocity = describeVelocity(v.velocity);
    info->moving = m.motion().moving();
    info->blurRadius = m.motion().blurRadius();
}

VolumeInfo describeVolume(const VolumeRecord& v, const Medium& m) {
    VolumeInfo info;
    info.file = v.file;
    if (!v.file.empty() && !isNanoVdb(v.file)) info.vdb = inspectVdbFile(v.file);
    info.shader = v.shader;
    info.shaderSource = m.shader().source;
    info.densityScale = v.densityScale;
    info.notes = v.notes;
    info.slots = slotsOf(v, m);
    info.expressions = v.expressions;
    info.unusedGrids = v.unusedGrids;
    describeMotion(v, m, &info);
    info.greyPath = m.greyPath();
    if (m.emissive() && !m.homogeneous()) {
        MediumEmitter emitter(m);
        info.emission =
            EmissionInfo{m.shader().emission->intensity, m.shader().emission->minTemperature,
                         emitter.emittingVoxels(), emitter.tablePower()};
    }
    info.worldBounds = m.worldBounds();
    info.majorantCells = {m.majorant().res(0), m.majorant().res(1), m.majorant().res(2)};
    info.maxSigmaT = m.majorant().maxValue();
    return info;
}

// Light `i`'s group, as the lightgroup_* passes name it ("" when no light has a group).
std::string lightGroupOf(const RenderScene& scene, size_t i) {
    if (scene.lightGroups.empty()) return "";
    const int slot = scene.lightGroupSlot(i);
    return slot == 0 ? "emission" : scene.lightGroupNames()[size_t(slot - 1)];
}

OutputInfo describeOutput(const Scene& scene) {
    const RenderSettings& s = scene.settings;
    OutputInfo out{scene.output.path,
                   scene.output.halfFloat,
                   scene.output.multipart,
                   s.aovs,
                   {},
                   {},
                   {},
                   s.deep};
    if (!scene.render.lightGroups.empty()) out.lightGroups = scene.render.lightGroupNames();
    for (const char* kind : {"volume", "shape"}) {
        const std::string pass = cryptomattePass(kind);
        if (std::find(s.aovs.begin(), s.aovs.end(), pass) == s.aovs.end()) continue;
        const CryptoObjects& o = scene.render.cryptoObjects;
        out.cryptomattes.push_back(
            {kind, pass, std::string(kind) == "volume" ? o.volumes : o.shapes});
    }
    for (size_t i = 0; i < scene.render.media.size(); ++i)
        if (scene.render.holdout(i)) out.holdouts.push_back("volume " + std::to_string(i));
    const GeometryScene* g = scene.render.geometry.get();
    for (size_t i = 0; g && i < g->shapeCount(); ++i)
        if (g->shape(int(i)).holdout) out.holdouts.push_back("shape " + std::to_string(i));
    return out;
}

// Why a scene's photon pass has no projection maps (photon/projection_map.h), "" when it has.
std::string noProjection(const Scene& scene, bool curved, const ProjectionPlan& plan) {
    if (scene.photon.projection == PhotonPassSettings::Projection::Off)
        return "[render] projection = \"off\", the default";
    if (curved) return "light curves in the [refraction] field";
    if (plan.targets == 0) return "no mirror or glass";
    if (!plan.any())
        return "every light's mirrors and glass take half its emission or more: its own photons "
               "are caustic photons";
    return "";
}

// Photons per map and the projection maps: how many caustic photons from which lights.
std::string describePhotons(const Scene& scene) {
    const PhotonIntegratorSettings& p = scene.photon;
    std::vector<const Light*> lights;
    for (const auto& l : scene.render.lights) lights.push_back(l.get());
    const Bounds3 bounds = scene.render.bounds();
    const bool curved = photonsCurve(p.field.get(), bounds);
    PhotonPassSettings pass = p;  // the field only where it bends light (photonsCurve)
    if (!curved) pass.field = nullptr;
    const ProjectionPlan plan =
        planProjection(lights, scene.render.hasSurfaces() ? scene.render.geometry.get() : nullptr,
                       bounds, projectionWanted(pass));
    std::string s = std::to_string(p.photons) + " per map; projection maps: ";
    const std::string why = noProjection(scene, curved, plan);
    if (!why.empty()) return s + "off (" + why + ")";
    size_t projected = 0;
    for (const auto& m : plan.maps) projected += bool(m);
    return s + "on, " + std::to_string(p.causticPhotonsOrDefault()) +
           " caustic photons per map from " + std::to_string(projected) + " of " +
           std::to_string(lights.size()) + " lights towards " + std::to_string(plan.targets) +
           " mirror and glass shapes";
}

}  // namespace

VolumeFileInfo describeVolumeFile(const std::string& path, int frame) {
    VolumeFileInfo info;
    info.file = expandFramePattern(path, frame);
    info.vdb = inspectVdbFile(info.file);
    if (info.vdb.format != "OpenVDB") return info;
    for (size_t i = 0; i < info.vdb.grids.size(); ++i) {
        const GridInfo& g = info.vdb.grids[i];
        if (g.valueType != "float" && g.valueType != "half" && g.valueType != "double") continue;
        const std::string name = gridName(g.name, i);
        const GridTopology topology = readGridTopology(info.file, name);
        SlotInfo grid;
        grid.slot = grid.grid = name;
        grid.activeVoxels = g.activeVoxels;
        grid.treeBytes = topology.floatTreeBytes;
        grid.leaves = topology.leaves;
        for (GridPrecision p : kAllPrecisions)
            grid.bytesAt[size_t(p)] =
                treeBytesAt(p, GridPrecision::Float, topology.floatTreeBytes, topology.leaves);
        info.grids.push_back(grid);
    }
    return info;
}

SceneInfo describeScene(const Scene& scene, const ColorPipeline& color) {
    SceneInfo info;
    for (size_t i = 0; i < scene.volumes.size(); ++i)
        info.volumes.push_back(describeVolume(scene.volumes[i], *scene.render.media[i]));
    for (size_t i = 0; i < scene.render.lights.size(); ++i)
        info.lights.push_back({scene.render.lights[i]->describe(), lightGroupOf(scene.render, i)});
    info.camera = scene.render.camera;
    info.shutter = scene.shutter;
    info.fps = scene.output.fps;
    info.film = scene.settings;
    info.passes = scene.passes;
    const IntegratorInfo& integrator = integratorInfo(scene.integrator);
    info.photonMapPerPass = integrator.photonPass;
    if (integrator.photonPass && scene.render.hasSurfaces())
        info.finalGather = scene.photon.finalGather;
    if (integrator.photonPass) info.photons = describePhotons(scene);
    info.integrator = scene.integrator;
    info.integratorDescription = integrator.description;
    info.integratorWhy = scene.integratorWhy;
    info.workingSpace = color.workingSpace();
    info.ocioConfig = color.configDescription();
    info.output = describeOutput(scene);
    info.physics = scene.physics();
    return info;
}

}  // namespace mirage
