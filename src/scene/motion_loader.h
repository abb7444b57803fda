// Velocity motion blur as a scene file asks for it: the shutter ([camera] shutter, in frames),
// the frame rate ([output] fps) and each volume's velocity grid ([[volume]] velocity,
// velocity_scale). The keys are documented in docs/scene-file.md, "Motion blur".
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/keyed_transform.h"
#include "medium/medium_motion.h"
#include "scene/toml_reader.h"
#include "volume/vector_grid.h"

namespace mirage {

class GridCache;

// The shutter in frames relative to the frame, as written: Houdini's centred [-0.25, 0.25] is
// a 180° shutter. open == close: no motion blur.
struct ShutterFrames {
    double open = 0.0, close = 0.0;
    bool blurs() const { return close != open; }
    // The largest |Δt| (seconds) a path may carry at `fps` frames per second.
    double maxTimeOffset(double fps) const {
        return std::max(std::abs(open), std::abs(close)) / fps;
    }
};

// [camera] shutter = [open, close] (frames, open ≤ close, each within ±1 frame).
ShutterFrames readShutter(const TableReader& camera);

// What a volume's velocity is bound to, for `mirage info` and the render summary.
struct VelocityRecord {
    std::string grid;  // the grid (or the stem of three scalar grids); "" for none
    std::string why;   // how it was chosen, or why there is none
    float scale = 1.f;
    VectorGrid velocity;  // loaded only when the shutter is open
};

// Reads `velocity` and `velocity_scale` of a [[volume]] and resolves the grid in `file`
// (grids: the file's grid names in order). Without the key, a grid named vel, v or velocity
// (a vector grid, or three scalar grids NAME.x/.y/.z) is taken; velocity = "" switches blur off.
// The grid is loaded when `load` (the shutter is open), through `cache` when there is one.
// Errors name the key's line.
VelocityRecord readVelocity(const TableReader& volume, const std::string& file,
                            const std::vector<std::string>& grids, bool load,
                            GridCache* cache = nullptr);
// The same for a bare VDB: the default names only.
VelocityRecord findVelocity(const std::string& file, const std::vector<std::string>& grids,
                            bool load, GridCache* cache = nullptr);

// One line describing the bound velocity (class, range of |v|), for reports.
std::string describeVelocity(const VelocityRecord& v);

// A volume's `transform` table and its `[[volume.transform.key]]` list: each key a `frame` and
// the parts it sets (scale, rotate, translate; the others are the table's), at seconds
// (key frame − frame) / fps. Without keys, one key at 0 holding the table's parts.
KeyedTransform readVolumeTransform(const TableReader& transform, int frame, double fps);

struct Scene;
struct VolumeRecord;

// The grid names of a VDB file in order (an unnamed grid as "#N"), where a velocity is sought.
std::vector<std::string> fileGridNames(const std::string& file);
// How a volume moves over the scene's shutter (medium/medium_motion.h, for Medium::setMotion):
// with its record's velocity grid, and along its keyed transform when the keys move it and the
// shutter is open. The grids the velocity reads are taken off the record's unused ones.
MediumMotion volumeMotion(const Scene& scene, const KeyedTransform& keys, VolumeRecord* rec);
// The camera's shutter in seconds, from the frames the scene (or the command line) gives.
void setShutterSeconds(Scene* scene);

}  // namespace mirage
