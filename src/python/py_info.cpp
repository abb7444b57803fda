// The record of `mirage info` (scene/scene_info.h) as Python dicts and lists: the fields of each
// struct under their names in snake case, vectors as 3-tuples, bounds as (lo, hi), byte counts
// as ints. What app/info_command.cpp prints, as data.
#include "python/py_info.h"

#include "film/cryptomatte.h"

namespace mirage::python {

namespace py = pybind11;

namespace {

py::tuple vec3(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }
py::tuple vec3(const Vec3d& v) { return py::make_tuple(v.x, v.y, v.z); }
py::tuple bounds(const Bounds3& b) { return py::make_tuple(vec3(b.lo), vec3(b.hi)); }

py::list strings(const std::vector<std::string>& v) {
    py::list out;
    for (const std::string& s : v) out.append(s);
    return out;
}

// One grid of a VDB file, as `mirage info` lists it.
py::dict gridDict(const GridInfo& g) {
    py::dict d;
    d["name"] = g.name;
    d["value_type"] = g.valueType;
    d["grid_class"] = g.gridClass;
    d["compression"] = g.compression;
    d["voxel_size"] = vec3(g.voxelSize);
    d["index_min"] = py::make_tuple(g.indexMin[0], g.indexMin[1], g.indexMin[2]);
    d["index_max"] = py::make_tuple(g.indexMax[0], g.indexMax[1], g.indexMax[2]);
    d["world_bounds"] = bounds(g.objectBounds);
    d["active_voxels"] = g.activeVoxels;
    d["memory_bytes"] = g.memoryBytes;
    d["transform"] = g.transform;
    return d;
}

py::dict vdbDict(const VdbFileInfo& f) {
    py::dict d;
    d["path"] = f.path;
    d["format"] = f.format;
    d["file_version"] = f.fileVersion;
    d["library_version"] = f.libraryVersion;
    py::list grids;
    for (const GridInfo& g : f.grids) grids.append(gridDict(g));
    d["grids"] = grids;
    return d;
}

// The grids bound to the shader's slots and the expressions run on them.
void addGridUse(const VolumeInfo& v, py::dict* d) {
    py::list slots;
    for (const SlotInfo& s : v.slots) {
        py::dict slot;
        slot["slot"] = s.slot;
        slot["grid"] = s.grid;
        slot["active_voxels"] = s.activeVoxels;
        slot["tree_bytes"] = s.treeBytes;
        slot["dense_bytes"] = s.denseBytes;
        slot["max_value"] = s.maxValue;
        slot["precision"] = precisionName(s.precision);
        py::dict bytesAt;  // the tree at every precision (scene/scene_info.h)
        for (GridPrecision p : kAllPrecisions) bytesAt[precisionName(p)] = s.bytesAt[size_t(p)];
        slot["tree_bytes_at"] = bytesAt;
        slots.append(slot);
    }
    (*d)["slots"] = slots;
    py::list expressions;
    for (const ExpressionRecord& e : v.expressions) {
        py::dict x;
        x["origin"] = e.origin;
        x["where"] = e.expression.where.str();
        x["code"] = e.expression.code;
        x["reads"] = strings(e.access.reads);
        x["writes"] = strings(e.access.writes);
        x["seconds"] = e.seconds;
        expressions.append(x);
    }
    (*d)["expressions"] = expressions;
    (*d)["unused_grids"] = strings(v.unusedGrids);
}

py::dict volumeDict(const VolumeInfo& v) {
    py::dict d;
    d["file"] = v.file;
    d["vdb"] = v.vdb ? py::object(vdbDict(*v.vdb)) : py::none();
    d["shader"] = v.shader;
    d["shader_source"] = v.shaderSource;
    d["density_scale"] = v.densityScale;
    d["notes"] = strings(v.notes);
    addGridUse(v, &d);
    d["velocity"] = v.velocity;
    d["moving"] = v.moving;
    d["blur_radius"] = v.blurRadius;
    d["transform_moves"] = v.transformMoves;
    d["grey_path"] = v.greyPath;
    if (v.emission) {
        py::dict e;
        e["intensity"] = v.emission->intensity;
        e["min_temperature"] = v.emission->minTemperature;
        e["voxels"] = v.emission->voxels;
        e["power"] = v.emission->power;
        d["emission"] = e;
    } else {
        d["emission"] = py::none();
    }
    d["world_bounds"] = bounds(v.worldBounds);
    d["majorant_cells"] =
        py::make_tuple(v.majorantCells[0], v.majorantCells[1], v.majorantCells[2]);
    d["max_sigma_t"] = v.maxSigmaT;
    return d;
}

py::dict cameraDict(const CameraDesc& c) {
    py::dict d;
    d["position"] = vec3(c.position);
    d["look_at"] = vec3(c.lookAt);
    d["up"] = vec3(c.up);
    d["fov"] = c.fovDeg;
    d["keys"] = c.keys.size();
    d["turntable"] = c.orbitDegreesPerSecond != 0.f;
    d["moves"] = c.moves();
    d["shutter_seconds"] = py::make_tuple(c.shutterOpen, c.shutterClose);
    return d;
}

// The film, its samples and passes, the integrator and the colour management.
py::dict filmDict(const SceneInfo& info) {
    const RenderSettings& f = info.film;
    py::dict d;
    d["resolution"] = py::make_tuple(f.width, f.height);
    d["spp"] = f.spp;
    d["tile_size"] = f.tileSize;
    d["seed"] = f.seed;
    d["passes"] = info.passes.maxPasses;
    d["pass_spp"] = info.passes.sppPerPass;
    d["photon_map_per_pass"] = info.photonMapPerPass;
    d["final_gather"] = info.finalGather;
    return d;
}

py::dict outputDict(const OutputInfo& out) {
    py::dict d;
    d["path"] = out.path;
    d["half_float"] = out.halfFloat;
    d["multipart"] = out.multipart;
    d["passes"] = strings(out.passes);
    d["light_groups"] = strings(out.lightGroups);
    py::list cryptomattes;
    for (const CryptomatteInfo& c : out.cryptomattes) {
        py::dict x;
        x["kind"] = c.kind;
        x["pass"] = c.pass;
        x["objects"] = strings(c.objects);
        cryptomattes.append(x);
    }
    d["cryptomattes"] = cryptomattes;
    d["holdouts"] = strings(out.holdouts);
    d["deep"] = out.deep.path.empty() ? py::object(py::none()) : py::object(py::str(out.deep.path));
    return d;
}

}  // namespace

py::dict infoDict(const SceneInfo& info) {
    py::dict d;
    py::list volumes;
    for (const VolumeInfo& v : info.volumes) volumes.append(volumeDict(v));
    d["volumes"] = volumes;
    py::list lights;
    for (const LightInfo& l : info.lights) {
        py::dict x;
        x["description"] = l.description;
        x["group"] = l.group;
        lights.append(x);
    }
    d["lights"] = lights;
    d["camera"] = cameraDict(info.camera);
    d["shutter"] = py::make_tuple(info.shutter.open, info.shutter.close);
    d["fps"] = info.fps;
    d["film"] = filmDict(info);
    d["integrator"] = info.integrator;
    d["integrator_description"] = info.integratorDescription;
    d["integrator_why"] = info.integratorWhy;
    d["working_space"] = info.workingSpace;
    d["ocio_config"] = info.ocioConfig;
    d["output"] = outputDict(info.output);
    py::dict physics;  // term → {active, why}, in the order `mirage info` prints them
    for (const PhysicsTerm& t : info.physics) {
        py::dict x;
        x["active"] = t.active;
        x["why"] = t.why;
        physics[py::str(t.name)] = x;
    }
    d["physics"] = physics;
    return d;
}

}  // namespace mirage::python
