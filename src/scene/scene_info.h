// What `mirage info` knows about a loaded scene, as data: each volume's grids, shader, slots,
// expressions, velocity and motion, coefficients path, emission and majorant; the lights and
// their groups; the camera and shutter; the film and integrator; what the render writes beside
// the beauty; the physics terms the scene switches on. app/info_command.cpp prints it; a
// program (the Python module's scene.info()) returns it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "volume/vdb_file.h"

namespace mirage {

class ColorPipeline;

// A grid bound to a shader slot, as loaded: the tree and, where the grid is small enough, the
// dense copy its lookups read (volume/dense_block.h); its precision, and its tree's bytes at
// every precision, by index of GridPrecision (volume/grid_precision.h, treeBytesAt: exact
// from its leaf count; fpn at its widest; 0, unknown, from a grid held at fpn).
struct SlotInfo {
    std::string slot, grid;
    uint64_t activeVoxels = 0, treeBytes = 0, denseBytes = 0;
    double maxValue = 0;
    GridPrecision precision = GridPrecision::Float;
    uint64_t leaves = 0;
    std::array<uint64_t, std::size(kAllPrecisions)> bytesAt = {};
    std::string precisionWhy;  // stated, or the default's reason (scene/precision_loader.h)
};

// An emissive grid volume: what the photon pass emits from (photon/medium_emitter.h).
struct EmissionInfo {
    double intensity = 0, minTemperature = 0;  // K
    size_t voxels = 0;                         // emitting voxels above minTemperature
    double power = 0;                          // W over 360–830 nm
};

struct VolumeInfo {
    std::string file;                // "" = a homogeneous box
    std::optional<VdbFileInfo> vdb;  // the file's grids (an OpenVDB file; none for NanoVDB)
    std::string shader, shaderSource;
    double densityScale = 1;
    std::vector<std::string> notes;  // a bare VDB: how its grids were bound, and why
    std::vector<SlotInfo> slots;
    std::vector<ExpressionRecord> expressions;
    std::vector<std::string> unusedGrids;  // read by no slot or expression: not loaded
    std::string velocity;  // describeVelocity (unloaded with the shutter closed); "" without a file
    bool moving = false;   // lookups advected within the shutter
    double blurRadius = 0;        // m: how far they move, and the majorant's dilation
    bool transformMoves = false;  // a keyed transform moves the volume within the shutter
    bool greyPath = false;        // every σ wavelength-independent, none fluoresces
    std::optional<EmissionInfo> emission;
    Bounds3 worldBounds;
    std::array<int, 3> majorantCells = {0, 0, 0};
    double maxSigmaT = 0;  // 1/m
};

struct LightInfo {
    std::string description;
    std::string group;  // its lightgroup_* pass; "" when no light has a group
};

// A Cryptomatte the render writes: its layers' name, and the objects it hashes.
struct CryptomatteInfo {
    std::string kind;  // "volume" or "shape"
    std::string pass;  // layers <pass>00, <pass>01, …
    std::vector<std::string> objects;
};

// What the render writes: the EXR and, beside the beauty, passes, light groups, Cryptomattes,
// holdouts and deep output (docs/aovs.md). A scene pays only for what it asks for.
struct OutputInfo {
    std::string path;
    bool halfFloat = true, multipart = false;
    std::vector<std::string> passes;
    std::vector<std::string> lightGroups;
    std::vector<CryptomatteInfo> cryptomattes;
    std::vector<std::string> holdouts;  // "volume 0", "shape 2"
    DeepSettings deep;                  // path "" = off
};

struct SceneInfo {
    std::vector<VolumeInfo> volumes;
    std::vector<LightInfo> lights;
    CameraDesc camera;
    ShutterFrames shutter;  // frames; camera holds it in seconds
    double fps = 24;
    RenderSettings film;
    PassSettings passes;
    bool photonMapPerPass = false;  // a render in passes whose integrator traces photons
    // The photon integrator on a scene with surfaces: its final gather rays at the first diffuse
    // surface (0: the global map read there); -1 for any other render.
    int finalGather = -1;
    // The photon pass's emission when the integrator traces photons (else ""): photons per map
    // and whether projection maps aim a caustic stream, and why not where they do not.
    std::string photons;
    std::string integrator, integratorDescription;
    std::string integratorWhy;  // "" when the scene or --set named it
    std::string workingSpace, ocioConfig;
    OutputInfo output;
    std::vector<PhysicsTerm> physics;
};

// What `mirage info FILE.vdb` says of a bare volume file without reading a voxel: its grids
// from the file's metadata, and for each scalar OpenVDB grid its leaves and tree bytes at every
// precision from its topology (SlotInfo's slot and grid both the grid's name; no maximum, no
// dense copy: those need the voxels).
struct VolumeFileInfo {
    std::string file;  // the path, its frame pattern filled in
    VdbFileInfo vdb;
    std::vector<SlotInfo> grids;
};

// The record of bare volume file `path` (a $F4 pattern filled in with `frame`), from its
// metadata and topology alone: gridReadCount() does not change. Throws MirageError for a
// missing or corrupt file.
VolumeFileInfo describeVolumeFile(const std::string& path, int frame);

// The record of `scene`, loaded through `color`. Reads each volume file's grid list (metadata),
// never a grid the load left unread. Throws MirageError for a file gone bad.
SceneInfo describeScene(const Scene& scene, const ColorPipeline& color);

}  // namespace mirage
