// A loaded scene: what the render stage needs (RenderScene), the render and output settings,
// and a record of what was loaded and why, for `mirage info`.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/curved_camera.h"
#include "render/passes.h"
#include "render/photon_integrator.h"
#include "render/render_scene.h"
#include "render/renderer.h"
#include "scene/motion_loader.h"
#include "volume/grid_expression.h"
#include "volume/grid_precision.h"

namespace mirage {

class ColorPipeline;
class GridCache;

struct OutputSettings {
    std::string path = "out/render.exr";  // may hold a frame pattern ($F4, ####)
    std::string colorSpace;               // "" = the working space
    bool halfFloat = true;
    std::string preview;                  // "" = none; else a PNG/JPEG path
    std::string display = "sRGB", view = "Standard";
    double fps = 24;  // frames per second: converts the shutter (frames) and velocities (1/s)
    bool multipart = false;  // AOVs as parts of their own (image_io.h ExrOptions::multipart)
};

// A grid expression as loaded: the code, where it came from, its grids and its cost.
struct ExpressionRecord {
    GridExpression expression;
    std::string origin;     // "volume" or "shader 'name'"
    ExpressionAccess access;  // grid names in the file
    double seconds = 0;     // compile + run (OpenVDB AX)
};

struct VolumeRecord {
    std::string file;  // after frame substitution
    std::string shader;
    std::vector<std::pair<std::string, std::string>> bindings;  // shader slot → grid in file
    // The shader's expression, then the volume's, in the order they run.
    std::vector<ExpressionRecord> expressions;
    // Grids in the file that no shader slot and no expression reads (not loaded).
    std::vector<std::string> unusedGrids;
    float densityScale = 1;
    PrecisionSpec precision;  // precision, precision_tolerance: how its scalar grids are held
    std::string precisionWhy;  // why that precision (scene/precision_loader.h, choosePrecision)
    VelocityRecord velocity;  // motion blur: the velocity grid bound, or why there is none
    std::vector<std::string> notes;  // a bare VDB: how its grids were bound, and why
};

struct PhysicsTerm {
    std::string name;
    bool active;
    std::string why;
};

struct Scene {
    std::string source;  // scene file or VDB file
    RenderScene render;
    RenderSettings settings;
    OutputSettings output;
    // [render] integrator: single | volpath | photon, or auto (the default), which the loader
    // resolves to one of them (chooseIntegrator) and explains in integratorWhy.
    std::string integrator = "auto";
    std::string integratorWhy;           // "" when the scene or --set named the integrator
    int maxDepth = 10000;                // [render] max_depth: scattering events per path
    // A render in passes: [render] pass_spp, and --passes, --time-limit, --noise-threshold.
    PassSettings passes;
    // [render] photons, estimate (beam | point), k, max_radius: the photon integrator's
    // settings (its seed and progress mode come from the render settings).
    PhotonIntegratorSettings photon;
    // film.spp and render.photons as the scene file states them (0: not stated): what the
    // scene needs at the preview preset, which the quality presets scale (frame_settings.h; a
    // stated render.k, nonzero, is kept).
    int statedSpp = 0;
    uint64_t statedPhotons = 0;
    // [render] passes as stated (0: not stated): the scene renders in that many passes of
    // pass_spp samples, a photon map each with the photon integrator (what k-nearest photon
    // estimates need to lose their noise: more photons in one map only shrink the radius).
    int statedPasses = 0;
    // [render] pass_spp as stated (0: not stated).
    int statedPassSpp = 0;
    // What `auto` set for rule 4 (integrator_choice.cpp) where the scene left it open, undone
    // when an integrator is named: statedPasses made from film.spp, pass_spp, the estimate's k,
    // the first pass's photons.
    struct AutoProgressive {
        bool passes = false, passSpp = false, k = false, firstPassPhotons = false;
    } autoSet;
    // [render] first_pass_photons was stated (0 included: as many as the other passes).
    bool statedFirstPassPhotons = false;
    int majorantResolution = 64;
    ShutterFrames shutter;  // [camera] shutter (frames); render.camera holds it in seconds
    std::vector<VolumeRecord> volumes;
    // [refraction]: camera rays bend in this index field; null when the scene has none (or its
    // gradient is 0 everywhere), and then nothing changes.
    std::shared_ptr<const Refraction> refraction;

    // Which physics terms this scene activates, and why ("model only what a scene requires").
    std::vector<PhysicsTerm> physics() const;
};

struct LoadOptions {
    int frame = 1;                        // substituted into $F patterns
    std::vector<std::string> overrides;   // --set key=value, applied before parsing
    // Called before each grid is read, with the scene so far (settings, media already built),
    // the file, the grid, the precision it will be held in and its in-core size there from the
    // file's metadata; may throw to stop the load (--max-memory refuses a grid that will not fit
    // before reading it).
    std::function<void(const Scene&, const std::string& file, const std::string& grid,
                       GridPrecision precision, uint64_t bytes)>
        beforeGridLoad = nullptr;
    // --shutter / --motion-blur: replaces the scene's [camera] shutter (and gives a bare VDB one).
    std::optional<ShutterFrames> shutter = std::nullopt;
    // --integrator: replaces the scene's [render] integrator before the loader resolves "auto"
    // (resolveAutoIntegrator, once); "" keeps the scene's.
    std::string integrator = "";
    // The scene file's text, when a program holds it (frame_request.h, sceneText): parsed
    // instead of reading `path`, which names it in messages and resolves its relative paths.
    std::string text = "";
    // Grids kept from earlier loads (volume/grid_cache.h): a file's grids are read again only
    // when it changed. Null: every load reads them.
    GridCache* grids = nullptr;
};

// The default integrator: the method that renders all of this scene's light and converges
// fastest (integrator_choice.cpp), and why, for `mirage info` and the render summary.
struct IntegratorChoice {
    std::string name;
    std::string why;
    bool progressive = false;  // render film.spp as progressive photon passes
};
IntegratorChoice chooseIntegrator(const Scene& scene);
// Replaces integrator "auto" by chooseIntegrator's choice and records why; any other name stays.
void resolveAutoIntegrator(Scene* scene);

Scene loadScene(const std::string& path, const LoadOptions& options, const ColorPipeline& color);
// A bare VDB: automatic camera framing its bounds, a key light, the built-in smoke shader
// bound to its density grid (or its only scalar grid).
Scene sceneFromVdb(const std::string& path, const LoadOptions& options, const ColorPipeline& color);
bool isVolumeFile(const std::string& path);  // .vdb or .nvdb

// "$F4" → frame zero-padded to 4 digits, "$F" → unpadded, a run of '#' → padded to its length.
std::string expandFramePattern(const std::string& pattern, int frame);
bool hasFramePattern(const std::string& pattern);
// "A-B" → frames A to B; "A-BxS" → every S-th frame from A (1-48x2: 1, 3, …, 47).
std::vector<int> parseFrameRange(const std::string& range);

// A camera looking at the bounds from the front and slightly above, far enough that the
// bounding sphere fills the vertical field of view.
CameraDesc frameBounds(const Bounds3& bounds, float fovDeg, float aspect);

// Irradiance (W/m²) under which a white Lambertian surface facing a flat-spectrum light has
// luminance-like Y = 1: E = π · (830 − 360) nm · 1 W·m⁻²·sr⁻¹·nm⁻¹.
constexpr float kUnitWhiteIrradiance = 3.14159265f * 470.f;

}  // namespace mirage
