#include "scene/motion_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/grid_name.h"
#include "scene/geometry_loader.h"
#include "scene/scene.h"
#include "volume/grid_cache.h"
#include "volume/vdb_file.h"

namespace mirage {

namespace {

bool contains(const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end();
}

bool hasScalarTriple(const std::vector<std::string>& names, const std::string& stem) {
    return contains(names, stem + ".x") && contains(names, stem + ".y") &&
           contains(names, stem + ".z");
}

// A name the file holds as one grid, or as the stem of three component grids; "" otherwise.
std::string resolveName(const std::vector<std::string>& names, const std::string& name) {
    if (contains(names, name) || hasScalarTriple(names, name)) return name;
    return "";
}

VectorGrid load(const std::string& file, const std::vector<std::string>& names,
                const std::string& grid, GridCache* cache) {
    const bool fromScalars = !contains(names, grid);
    if (cache) return cache->loadVectorGrid(file, grid, fromScalars);
    return fromScalars ? loadVectorGridFromScalars(file, grid) : loadVectorGrid(file, grid);
}

}  // namespace

ShutterFrames readShutter(const TableReader& camera) {
    ShutterFrames s;
    if (!camera.has("shutter")) return s;
    const std::vector<double> v = camera.getNumbers("shutter", 2, 2);
    // Beyond a frame either way a shutter overlaps the neighbouring frames' exposures: almost
    // always degrees (180) or seconds written where frames were meant.
    if (!(v[0] <= v[1]) || !(v[0] >= -1.0) || !(v[1] <= 1.0))
        camera.fail("shutter",
                    "expected [open, close] in frames relative to the frame, "
                    "open ≤ close, each within [-1, 1] (Houdini's default is "
                    "[-0.25, 0.25]; [0, 0] switches motion blur off)");
    s.open = v[0];
    s.close = v[1];
    return s;
}

VelocityRecord findVelocity(const std::string& file, const std::vector<std::string>& grids,
                            bool load_, GridCache* cache) {
    VelocityRecord r;
    for (const char* n : {"vel", "v", "velocity"}) {
        r.grid = resolveName(grids, n);
        if (!r.grid.empty()) break;
    }
    if (r.grid.empty()) {
        r.why = "no grid named vel, v or velocity: the volume is still";
        return r;
    }
    r.why = "found by its name";
    if (load_) r.velocity = load(file, grids, r.grid, cache);
    return r;
}

VelocityRecord readVelocity(const TableReader& volume, const std::string& file,
                            const std::vector<std::string>& grids, bool load_, GridCache* cache) {
    const float scale = float(volume.getNumber("velocity_scale", 1.0, -1e6, 1e6));
    if (!volume.has("velocity")) {
        VelocityRecord r = findVelocity(file, grids, load_, cache);
        r.scale = scale;
        return r;
    }
    VelocityRecord r;
    r.scale = scale;
    const std::string name = volume.getString("velocity");
    if (name.empty()) {
        r.why = "velocity = \"\": motion blur off for this volume";
        return r;
    }
    r.grid = resolveName(grids, name);
    if (r.grid.empty()) {
        std::string list;
        for (const auto& g : grids) list += (list.empty() ? "'" : ", '") + g + "'";
        volume.fail("velocity", file + " has no grid '" + name + "' and no grids '" + name +
                                    ".x', '" + name + ".y', '" + name + ".z' (it has: " + list +
                                    ")");
    }
    r.why = "named by 'velocity'";
    if (load_) {
        try {
            r.velocity = load(file, grids, r.grid, cache);
        } catch (const MirageError& e) {
            volume.fail("velocity", e.what());
        }
    }
    return r;
}

std::string describeVelocity(const VelocityRecord& v) {
    if (v.grid.empty()) return v.why;
    char buf[256];
    if (!v.velocity.valid()) {
        std::snprintf(buf, sizeof buf,
                      "grid '%s' (%s), velocity_scale %g; not loaded: the "
                      "shutter is closed",
                      v.grid.c_str(), v.why.c_str(), double(v.scale));
        return buf;
    }
    std::snprintf(buf, sizeof buf,
                  "grid '%s' (%s): %s, |v| %.3g to %.3g m/s over %llu active voxels (bound "
                  "%.3g), velocity_scale %g",
                  v.grid.c_str(), v.why.c_str(),
                  v.velocity.staggered() ? "staggered (face-centred, MAC)" : "collocated",
                  double(v.velocity.minMagnitude()), double(v.velocity.maxMagnitude()),
                  (unsigned long long)v.velocity.activeVoxels(),
                  double(v.velocity.magnitudeBound()), double(v.scale));
    std::string s = buf;
    if (v.velocity.sanitizedVoxels() > 0)
        s += "; " + std::to_string(v.velocity.sanitizedVoxels()) +
             " voxel(s) changed by the vector voxel rule";
    return s;
}

// The file's grid names in order (unnamed ones as "#N"), for the velocity lookup.
std::vector<std::string> fileGridNames(const std::string& file) {
    std::vector<std::string> names;
    const VdbFileInfo info = inspectVdbFile(file);
    for (size_t i = 0; i < info.grids.size(); ++i) names.push_back(gridName(info.grids[i].name, i));
    return names;
}

KeyedTransform readVolumeTransform(const TableReader& t, int frame, double fps) {
    const TransformParts base = readTransformParts(t);
    std::vector<TransformKey> keys;
    for (const TableReader& k : t.tables("key")) {
        if (!k.has("frame")) k.fail("frame", "a transform key needs the frame it holds at");
        TransformKey key;
        const double f = k.getNumber("frame", 0.0, -1e9, 1e9);
        key.time = (f - double(frame)) / fps;
        for (const TransformKey& o : keys)
            if (o.time == key.time) k.fail("frame", "two transform keys at the same frame");
        key.parts = readTransformParts(k, base);
        k.finish();
        keys.push_back(key);
    }
    t.finish();
    if (keys.empty()) keys.push_back(TransformKey{0.0, base});
    return KeyedTransform(std::move(keys));
}

MediumMotion volumeMotion(const Scene& scene, const KeyedTransform& keys, VolumeRecord* rec) {
    MediumMotion motion;
    const VelocityRecord& v = rec->velocity;
    if (v.velocity.valid())
        motion.setVelocity(v.velocity, v.scale,
                           float(scene.shutter.maxTimeOffset(scene.output.fps)));
    auto& unused = rec->unusedGrids;
    for (const std::string& n : {v.grid, v.grid + ".x", v.grid + ".y", v.grid + ".z"})
        unused.erase(std::remove(unused.begin(), unused.end(), n), unused.end());
    if (keys.moves() && scene.shutter.blurs())
        motion.setTransformKeys(keys, float(scene.shutter.open / scene.output.fps),
                                float(scene.shutter.close / scene.output.fps));
    return motion;
}

// The camera's shutter in seconds from the frames the scene (or the command line) gives.
void setShutterSeconds(Scene* scene) {
    scene->render.camera.shutterOpen = float(scene->shutter.open / scene->output.fps);
    scene->render.camera.shutterClose = float(scene->shutter.close / scene->output.fps);
}

}  // namespace mirage
