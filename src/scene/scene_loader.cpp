// Scene files (TOML) → Scene. The schema is documented in docs/scene-file.md; every
// table is read through TableReader, so unknown keys, wrong types and out-of-range values are
// errors naming the file, line and column.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>

#include "core/grid_name.h"
#include "core/path_check.h"
#include "core/text.h"
#include "film/color.h"
#include "medium/ocean_components.h"
#include "scene/camera_loader.h"
#include "scene/geometry_loader.h"
#include "scene/light_loader.h"
#include "scene/memory_budget.h"
#include "scene/output_loader.h"
#include "scene/photon_keys.h"
#include "scene/precision_loader.h"
#include "scene/pyro_binding.h"
#include "scene/refraction_loader.h"
#include "scene/scene.h"
#include "scene/shader_loader.h"
#include "scene/toml_reader.h"
#include "volume/grid_cache.h"
#include "volume/grid_quantise.h"
#include "volume/vdb_file.h"

namespace mirage {

namespace fs = std::filesystem;

bool isVolumeFile(const std::string& path) {
    auto ext = fs::path(path).extension().string();
    return ext == ".vdb" || ext == ".nvdb";
}

CameraDesc frameBounds(const Bounds3& b, float fovDeg, float aspect) {
    CameraDesc c;
    c.fovDeg = fovDeg;
    c.lookAt = b.center();
    float radius = 0.5f * length(b.diagonal());
    // Fit the bounding sphere in the narrower of the two fields of view, with a 5 % margin.
    float halfV = radians(fovDeg) * 0.5f;
    float halfH = std::atan(std::tan(halfV) * aspect);
    float half = std::min(halfV, halfH);
    float dist = 1.05f * radius / std::sin(half);
    Vec3 dir = normalize(Vec3(0.f, 0.2f, 1.f));
    c.position = c.lookAt + dir * dist;
    c.up = Vec3(0, 1, 0);
    return c;
}

TransformParts readTransformParts(const TableReader& t, const TransformParts& def) {
    TransformParts parts = def;
    if (t.has("scale")) {
        const toml::node* n = t.node("scale");
        Vec3d s = n->is_number() ? Vec3d(t.getNumber("scale")) : Vec3d(t.getVec3("scale"));
        if (s.x == 0 || s.y == 0 || s.z == 0) t.fail("scale", "a zero scale collapses the volume");
        // Grids already span 1e-5 m to 1e4 m voxels; a scale beyond 1e±6 on top of that leaves
        // single-precision ray parameters and bounds (float) without a useful digit.
        for (double c : {s.x, s.y, s.z})
            if (!(std::abs(c) >= 1e-6 && std::abs(c) <= 1e6)) {
                char found[32];
                std::snprintf(found, sizeof found, "%g", c);
                t.fail("scale", std::string("expected each scale factor's magnitude from 1e-6 "
                                            "to 1e6, found ") + found);
            }
        parts.scale = s;
    }
    if (t.has("rotate")) {
        auto r = t.getNumbers("rotate", 4, 4);
        Vec3d axis(r[1], r[2], r[3]);
        if (!(length(axis) > 0)) t.fail("rotate", "expected [degrees, axis x, y, z] with a non-zero axis");
        parts.degrees = r[0];
        parts.axis = normalize(axis);
    }
    if (t.has("translate")) parts.translate = Vec3d(t.getVec3("translate"));
    return parts;
}

Transform readTransform(const TableReader& t) {
    const Transform xf = readTransformParts(t).compose();
    t.finish();
    return xf;
}

namespace {

// Resolves the grid each shader slot binds to, checking it exists in the file.
std::vector<std::pair<std::string, std::string>> bindGrids(
    const ShaderDesc& shader, const std::vector<std::pair<std::string, std::string>>& explicitBind,
    const std::string& file, std::vector<std::string>* unused, const FileLoc& where) {
    std::vector<std::string> names;
    bool nano = fs::path(file).extension() == ".nvdb";
    if (!nano)
        for (const auto& g : inspectVdbFile(file).grids) names.push_back(g.name);
    auto slots = shader.gridSlots();
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& slot : slots) {
        std::string target = slot;
        bool bound = false;  // named by the scene's bind table: never replaced by a guess
        for (const auto& [s, g] : explicitBind)
            if (s == slot) {
                target = g;
                bound = true;
            }
        bool isIndex = !target.empty() && target[0] == '#';
        // "#N" must name one of the file's grids (checked here, where the scene line is known).
        bool indexInRange = false;
        if (isIndex && !nano) {
            const std::string digits = target.substr(1);
            indexInRange = !digits.empty() && digits.size() < 10 &&
                           digits.find_first_not_of("0123456789") == std::string::npos &&
                           std::stoul(digits) < names.size();
        }
        bool found = (isIndex && (nano || indexInRange)) || nano ||
                     std::find(names.begin(), names.end(), target) != names.end();
        if (!found && !bound && slots.size() == 1 && names.size() == 1) {
            target = gridName(names[0], 0);  // the file's only grid
            found = true;
        }
        if (nano && slots.size() == 1 && target == slot) target = gridIndexName(0);
        if (!found) {
            std::vector<std::string> quoted;
            for (size_t i = 0; i < names.size(); ++i) quoted.push_back(quotedGridName(names[i], i));
            throw MirageError(where, "shader '" + shader.name + "' reads grid slot '" + slot +
                                         "', but " + file + " has no grid '" + target +
                                         "' (it has: " + joinList(quoted) + "); bind one with bind = { " +
                                         slot + " = \"<grid>\" }");
        }
        out.emplace_back(slot, target);
    }
    if (unused)
        for (size_t i = 0; i < names.size(); ++i) {
            bool used = false;
            for (const auto& b : out) used |= b.second == names[i] || b.second == gridIndexName(i);
            if (!used) unused->push_back(gridName(names[i], i));
        }
    return out;
}

}  // namespace

// A shader's own expression, if it has one, runs first on every volume that uses the shader.
static void addShaderExpression(const ShaderDesc& shader, VolumeRecord* rec) {
    if (shader.expression.empty()) return;
    rec->expressions.push_back({{shader.expression, shader.expressionLoc,
                                 "'expression' of shader '" + shader.name + "'", {}},
                                "shader '" + shader.name + "'", {}, 0.0});
}

// Builds a medium from a shader and a file: loads only the grids the shader's slots and the
// expressions (rec.expressions, run in order on the OpenVDB grids) read.
static std::unique_ptr<Medium> buildMedium(const ShaderDesc& shader, VolumeRecord& rec,
                                           const std::vector<std::pair<std::string, std::string>>& explicitBind,
                                           const Transform& xf, int majorantRes,
                                           const FileLoc& where, const Scene& scene,
                                           const LoadOptions& options) {
    std::vector<std::string> unbound;
    rec.bindings = bindGrids(shader, explicitBind, rec.file, &unbound, where);
    // The shader's expression speaks of its slots: AX looks each one up under the grid the
    // volume binds it to.
    for (ExpressionRecord& e : rec.expressions) {
        if (e.origin != "volume")
            for (const auto& [slot, gridName] : rec.bindings)
                if (slot != gridName) e.expression.bindings.emplace_back(slot, gridName);
        e.access = expressionAccess(e.expression);
    }
    // Grids to read: the bound ones, then those only an expression names.
    std::vector<std::string> toRead;
    for (const auto& b : rec.bindings) toRead.push_back(b.second);
    for (const ExpressionRecord& e : rec.expressions)
        for (const auto* names : {&e.access.reads, &e.access.writes})
            for (const std::string& n : *names)
                if (std::find(toRead.begin(), toRead.end(), n) == toRead.end()) toRead.push_back(n);
    for (const std::string& u : unbound)
        if (std::find(toRead.begin(), toRead.end(), u) == toRead.end())
            rec.unusedGrids.push_back(u);
    // The file's metadata (cheap: no voxels are read): each grid's storage and in-core size.
    const VdbFileInfo info = inspectVdbFile(rec.file);
    std::vector<GridInfo> readInfo;
    for (const std::string& gridName : toRead)
        for (size_t i = 0; i < info.grids.size(); ++i)
            if (info.grids[i].name == gridName || gridIndexName(i) == gridName)
                readInfo.push_back(info.grids[i]);
    bool expressionWrites = false;
    for (const ExpressionRecord& e : rec.expressions)
        expressionWrites = expressionWrites || !e.access.writes.empty();
    const PrecisionChoice precision = choosePrecision(rec.precision, readInfo, expressionWrites);
    rec.precision = precision.spec;
    rec.precisionWhy = precision.why;
    if (options.beforeGridLoad) {
        for (const std::string& gridName : toRead) {
            uint64_t bytes = 0;
            for (size_t i = 0; i < info.grids.size(); ++i)
                if (info.grids[i].name == gridName || gridIndexName(i) == gridName)
                    bytes = gridBytesBeforeLoad(info.grids[i], rec.precision.precision);
            options.beforeGridLoad(scene, rec.file, gridName, rec.precision.precision, bytes);
        }
    }
    std::vector<std::string> bound;
    for (const auto& b : rec.bindings) bound.push_back(b.second);
    std::vector<GridExpression> expressions;
    for (const ExpressionRecord& e : rec.expressions) expressions.push_back(e.expression);
    std::vector<double> seconds;
    std::vector<FloatGrid> grids =
        options.grids
            ? options.grids->loadFloatGrids(rec.file, bound, expressions, &seconds, rec.precision)
            : loadGridsAt(rec.file, bound, expressions, &seconds, rec.precision);
    for (size_t i = 0; i < seconds.size() && i < rec.expressions.size(); ++i)
        rec.expressions[i].seconds = seconds[i];
    try {
        return std::make_unique<Medium>(shader, std::move(grids), xf, rec.densityScale,
                                        majorantRes);
    } catch (const MirageError& e) {
        // The medium names shader, component and grid; the scene names where it was asked for.
        if (e.location().line > 0) throw;
        if (where.line == 0) throw MirageError(rec.file + ": " + e.what());
        throw MirageError(where, rec.file + ": " + e.what());
    }
}

// [film], [render] and [output]: the settings a bare VDB takes from --set as well.
static void readSettings(const TableReader& top,
                         const std::function<std::string(const std::string&)>& resolve,
                         const ColorPipeline& color, Scene* out) {
    Scene& scene = *out;
    if (auto f = top.optionalTable("film")) {
        if (f->has("resolution")) {
            auto r = f->getNumbers("resolution", 2, 2);
            if (r[0] < 1 || r[1] < 1 || r[0] > 65536 || r[1] > 65536 || r[0] != std::floor(r[0]) ||
                r[1] != std::floor(r[1]))
                f->fail("resolution", "expected two whole numbers from 1 to 65536");
            scene.settings.width = int(r[0]);
            scene.settings.height = int(r[1]);
        }
        scene.settings.tileSize = int(f->getInt("tile_size", 32, 1, 4096));
        scene.settings.spp = int(f->getInt("spp", 16, 1, 1 << 20));
        if (f->has("spp")) scene.statedSpp = scene.settings.spp;
        scene.settings.seed = uint64_t(f->getInt("seed", 0, 0, INT64_MAX));
        f->finish();
    }
    if (auto r = top.optionalTable("render")) {
        scene.integrator = r->getString("integrator", "auto");
        try {
            if (scene.integrator != "auto") integratorInfo(scene.integrator);
        } catch (const MirageError& e) {
            r->fail("integrator", std::string(e.what()) + ", or auto (the default)");
        }
        scene.maxDepth = int(r->getInt("max_depth", 10000, 1, 1 << 30));
        scene.passes.sppPerPass =
            int(r->getInt("pass_spp", PassSettings{}.sppPerPass, 1, kMaxSamplesPerPixel));
        if (r->has("pass_spp")) scene.statedPassSpp = scene.passes.sppPerPass;
        if (r->has("passes")) {
            scene.statedPasses = int(r->getInt("passes", 1, 1, kMaxSamplesPerPixel));
            scene.passes.maxPasses = scene.statedPasses;
        }
        scene.settings.sampler = r->getChoice("sampler", "sobol", "random", "sampler")
                                     ? SamplerKind::Sobol
                                     : SamplerKind::Random;
        scene.render.equiangular =
            r->getChoice("lamp_sampling", "equiangular", "distance", "lamp sampling");
        scene.render.emissionSampling =
            r->getChoice("emission_sampling", "line", "flight", "emission sampling");
        scene.majorantResolution = int(r->getInt("majorant_resolution", 64, 1, 1024));
        readPhotonKeys(*r, &scene);
        r->finish();
    }
    if (auto o = top.optionalTable("output")) {
        scene.output.path = resolve(o->getString("path", "render.exr"));
        scene.output.colorSpace = o->getString("color_space", "");
        scene.output.halfFloat = o->getBool("half", true);
        std::string preview = o->getString("preview", "");
        scene.output.preview = preview.empty() ? "" : resolve(preview);
        scene.output.display = o->getString("display", "sRGB");
        scene.output.view = o->getString("view", "Standard");
        // Checked here, against the OCIO config in use, so that the message names the line.
        if (auto miss = findUnknownOutputName(color, scene.output.colorSpace,
                                              scene.output.display, scene.output.view))
            o->fail(miss->key, "'" + miss->value + "' is not in the OCIO config; it has: " +
                                   joinList(miss->known));
        scene.output.fps = o->getNumber("fps", 24.0, 1e-3, 1e6);
        // Checked once the lights (and their groups) are known: checkAovs.
        scene.settings.aovs = o->getStrings("aovs");
        readCryptomatte(*o, &scene);
        scene.output.multipart = o->getBool("multipart", false);
        readDeepSettings(*o, resolve, &scene);
        o->finish();
    }
}


namespace {

using Resolve = std::function<std::string(const std::string&)>;

// The volume's file for this frame: resolved from the scene's folder and present.
std::string readVolumeFile(const TableReader& v, const Resolve& resolve, int frame) {
    std::string file;
    try {
        file = resolve(expandFramePattern(v.getString("file"), frame));
    } catch (const MirageError& e) {
        v.fail("file", e.what());
    }
    // The shipped scenes use procedural caches that Mirage writes itself (no downloads): say
    // how, since a fresh checkout has none of them.
    if (const std::string problem = pathProblem(file); !problem.empty())
        v.fail("file", "volume file " + problem + ": " + file +
                           " (a procedural cache? `mirage make-asset KIND -o " + file +
                           "` writes one, `mirage make-asset --help` lists the kinds; the "
                           "scene's header "
                           "comment says which)");
    return file;
}

// The volume's shader (a name or a file next to the scene) with the volume's own component
// concentrations: concentration = { name = value, … } (what `mirage slab --set name=value`
// sets), e.g. --set volume.0.concentration.chlorophyll=5.
ShaderDesc readVolumeShader(const TableReader& v, const std::string& name,
                            const std::string& dir) {
    ShaderDesc shader;
    try {
        shader = loadShader(name, dir);
    } catch (const MirageError& e) {
        if (e.location().line > 0) throw;  // an error inside the shader file itself
        v.fail("shader", e.what());
    }
    if (auto c = v.optionalTable("concentration")) {
        for (const auto& k : c->keys()) {
            auto& comps = shader.components;
            auto it = std::find_if(comps.begin(), comps.end(),
                                   [&](const MediumComponent& mc) { return mc.name == k; });
            if (it == comps.end())
                c->fail(k, "shader '" + shader.name + "' has no component '" + k +
                               "'; its components are: " +
                               joinList(comps, [](const MediumComponent& mc) { return mc.name; }));
            it->concentration = float(c->getNumber(k, 0.0, 0.0, 1e12));
            it->covariesWith.clear();  // a stated a_y(440): Case-2 water
        }
        c->finish();
    }
    try {
        applyCase1Cdom(&shader);
    } catch (const MirageError& e) {
        v.fail("shader", e.what());
    }
    return shader;
}

// Per-volume exposure of the blackbody emission: multiplies the shader's `intensity` (1 =
// physical Planck radiance; 2 = one stop brighter, same colour).
void readEmissionIntensity(const TableReader& v, ShaderDesc* shader) {
    if (!v.has("emission_intensity")) return;
    const double k = v.getNumber("emission_intensity", 1.0, 0.0, 1e12);
    if (!shader->emission)
        v.fail("emission_intensity", "shader '" + shader->name +
                                         "' has no [emission] table, so there is no "
                                         "emission to scale");
    shader->emission->intensity *= float(k);
}

// bind = { slot = "grid", … }: which grid of the file each of the shader's slots reads.
std::vector<std::pair<std::string, std::string>> readBindings(const TableReader& v,
                                                              const ShaderDesc& shader) {
    std::vector<std::pair<std::string, std::string>> bind;
    if (auto b = v.optionalTable("bind")) {
        for (const auto& k : b->keys()) {
            auto slots = shader.gridSlots();
            if (std::find(slots.begin(), slots.end(), k) == slots.end())
                b->fail(k, "shader '" + shader.name + "' has no grid slot '" + k +
                               "'; its slots are: " + joinList(slots));
            bind.emplace_back(k, b->getString(k));
        }
    }
    return bind;
}

// Grid expressions (OpenVDB AX): the shader's first, over its slots, then the volume's, over
// the file's grid names (docs/scene-file.md, "Grid expressions").
void readExpressions(const TableReader& v, const ShaderDesc& shader, bool boxed,
                     VolumeRecord* rec) {
    addShaderExpression(shader, rec);
    if (v.has("expression")) {
        const std::string code = v.getString("expression");
        if (code.find_first_not_of(" \t\r\n") == std::string::npos)
            v.fail("expression", "expected OpenVDB AX code, e.g. \"@density = "
                                 "clamp((@density - 0.05) * 4, 0, 1);\"");
        rec->expressions.push_back(
            {{code, v.loc("expression"), "'expression' in [volume]", {}}, "volume", {}, 0.0});
    }
    if (boxed && !rec->expressions.empty())
        v.fail(v.has("expression") ? "expression" : "box",
               "a box volume has no grids for an expression to run on");
}

// box = { min = [...], max = [...] }: a homogeneous medium, so its shader reads no grid.
Bounds3 readVolumeBox(const TableReader& v, const ShaderDesc& shader) {
    TableReader b = v.table("box");
    Vec3 lo = b.getVec3("min"), hi = b.getVec3("max");
    if (!(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z))
        b.fail("max", "expected every coordinate of 'max' above that of 'min' (metres)");
    b.finish();
    Bounds3 box;
    box.expand(lo);
    box.expand(hi);
    auto slots = shader.gridSlots();
    if (!slots.empty())
        v.fail("box", "a box volume is homogeneous, but shader '" + shader.name +
                          "' reads grid slot(s) " +
                          joinList(slots, [](const std::string& sl) { return "'" + sl + "'"; }) +
                          "; use a 'file', or a shader whose components have no grid");
    return box;
}

// One [[volume]]: a VDB file (or a box) seen through a shader; its medium joins the scene.
void readVolume(const TableReader& v, const Resolve& resolve, const std::string& dir,
                const LoadOptions& options, Scene* scene) {
    VolumeRecord rec;
    // `box` instead of `file`: a homogeneous medium (a shader without grids) filling a box.
    const bool boxed = v.has("box");
    if (boxed && v.has("file")) v.fail("box", "give either 'file' or 'box', not both");
    const FileLoc where = v.loc(boxed ? "box" : "file");
    if (!boxed) rec.file = readVolumeFile(v, resolve, options.frame);
    rec.shader = v.getString("shader", "smoke");
    ShaderDesc shader = readVolumeShader(v, rec.shader, dir);
    rec.densityScale = float(v.getNumber("density_scale", 1.0, 0.0, 1e12));
    rec.precision = readVolumePrecision(v, boxed);
    readEmissionIntensity(v, &shader);
    const auto bind = readBindings(v, shader);
    readExpressions(v, shader, boxed, &rec);
    // The volume's transform at the frame, and its keys over the shutter.
    KeyedTransform keys;
    if (auto t = v.optionalTable("transform"))
        keys = readVolumeTransform(*t, options.frame, scene->output.fps);
    const Transform xf = keys.at(0.0);
    Bounds3 box;
    if (boxed) box = readVolumeBox(v, shader);
    // The velocity grid is read only when the shutter opens (it is read before the volumes).
    if (!boxed)
        rec.velocity = readVelocity(v, rec.file, fileGridNames(rec.file), scene->shutter.blurs(),
                                    options.grids);
    const bool holdout = v.getBool("holdout", false);
    scene->render.cryptoObjects.volumes.push_back(
        readObjectName(v, "volume" + std::to_string(scene->render.media.size())));
    v.finish();
    auto medium = boxed ? std::make_unique<Medium>(shader, box, xf, rec.densityScale)
                        : buildMedium(shader, rec, bind, xf, scene->majorantResolution, where,
                                      *scene, options);
    try {
        medium->setMotion(volumeMotion(*scene, keys, &rec));
    } catch (const MirageError& e) {
        v.fail(v.has("velocity") ? "velocity" : "file", e.what());
    }
    scene->render.media.push_back(std::move(medium));
    scene->render.mediumHoldouts.resize(scene->render.media.size());
    scene->render.mediumHoldouts.back() = holdout;
    scene->volumes.push_back(std::move(rec));
}

// A medium inside a closed shape exists only there, and the other media not there (glass
// sphere of ink in fog, water in a tank).
void confineInteriorMedia(Scene* scene) {
    const GeometryScene* geometry = scene->render.geometry.get();
    if (!geometry) return;
    std::vector<Confinement> where(scene->render.media.size());
    for (size_t i = 0; i < geometry->shapeCount(); ++i) {
        int m = geometry->shape(int(i)).interiorMedium;
        if (m < 0) continue;
        auto region = geometry->interiorRegion(int(i));
        for (size_t j = 0; j < where.size(); ++j) {
            if (int(j) == m)
                where[j].confineTo(region);
            else
                where[j].excludeFrom(region);
        }
    }
    for (size_t j = 0; j < where.size(); ++j)
        scene->render.media[j]->setConfinement(std::move(where[j]));
}

// [refraction]; a field with ∇n = 0 everywhere bends nothing: the scene renders as without it.
void readSceneRefraction(const TableReader& top, Scene* scene) {
    auto t = top.optionalTable("refraction");
    if (!t) return;
    scene->refraction = readRefraction(*t, scene->render.media);
    const Vec3d big(1e30);
    if (scene->refraction->field->gradientBound(-big, big) == 0) scene->refraction.reset();
}

// The integrator the load was asked for (--integrator), else the scene's, with "auto" resolved:
// the one place a loaded scene's integrator is chosen.
void useIntegrator(const LoadOptions& options, Scene* scene) {
    if (!options.integrator.empty()) scene->integrator = options.integrator;
    resolveAutoIntegrator(scene);
}

}  // namespace

Scene loadScene(const std::string& path, const LoadOptions& options, const ColorPipeline& color) {
    if (isVolumeFile(path)) return sceneFromVdb(path, options, color);
    toml::table doc =
        options.text.empty() ? parseTomlFile(path) : parseTomlText(options.text, path);
    for (const auto& o : options.overrides) applyOverride(doc, o);
    // A scene given as a bare file name lives in the working directory: its relative paths
    // (shaders, volumes, meshes) resolve from "." like any other scene's from its folder.
    std::string dir = fs::path(path).parent_path().string();
    if (dir.empty()) dir = ".";
    const Resolve resolve = [&](const std::string& p) {
        return fs::path(p).is_relative() ? (fs::path(dir) / p).string() : p;
    };

    Scene scene;
    scene.source = path;
    TableReader top(doc, path, "");
    readSettings(top, resolve, color, &scene);
    // The shutter before the volumes: a velocity grid is read only when it opens.
    if (options.shutter)
        scene.shutter = *options.shutter;
    else if (auto c = top.optionalTable("camera"))
        scene.shutter = readShutter(*c);
    for (const auto& v : top.tables("volume")) readVolume(v, resolve, dir, options, &scene);
    readLights(top, color, resolve, &scene.render);
    EmissiveTriangles emitters;
    scene.render.geometry =
        readGeometry(top, resolve, scene.render.media.size(), color, &emitters);
    addSurfaceLight(std::move(emitters), &scene.render);
    for (size_t i = 0; scene.render.geometry && i < scene.render.geometry->shapeCount(); ++i)
        scene.render.cryptoObjects.shapes.push_back(scene.render.geometry->shape(int(i)).name);
    checkAovs(top, scene);
    confineInteriorMedia(&scene);
    scene.render.camera = readCamera(top, options.frame, scene);
    setShutterSeconds(&scene);
    readSceneRefraction(top, &scene);
    top.finish();
    useIntegrator(options, &scene);
    return scene;
}

Scene sceneFromVdb(const std::string& path, const LoadOptions& options, const ColorPipeline& color) {
    Scene scene;
    scene.source = path;
    VolumeRecord rec;
    rec.file = expandFramePattern(path, options.frame);
    if (const std::string problem = pathProblem(rec.file); !problem.empty())
        throw MirageError("volume file " + problem + ": " + rec.file);
    if (!options.overrides.empty()) {
        // No scene file: --set reaches the settings tables only; anything else (a light, a
        // volume, a typo) is an unknown key rather than silently ignored.
        toml::table doc;
        for (const auto& o : options.overrides) applyOverride(doc, o);
        TableReader top(doc, "--set (bare volume " + path + ")", "");
        readSettings(top, [](const std::string& p) { return p; }, color, &scene);
        top.finish();
    }
    // Smoke, or a pyro cache's fire (scene/pyro_binding.h).
    const std::vector<std::string> names = fileGridNames(rec.file);
    const PyroBinding pyro = bindPyroCache(names, [&](const std::string& g) {
        return loadFloatGrids(rec.file, {g}, {}).front().maxValue();
    });
    rec.shader = pyro.shader;
    rec.notes = pyro.notes;
    ShaderDesc shader = loadShader(pyro.shader, "");
    if (pyro.shader == "fire") adaptFireShader(pyro, &shader);
    // A smoke.toml in $MIRAGE_SHADER_PATH may carry an expression of its own.
    addShaderExpression(shader, &rec);
    if (options.shutter) scene.shutter = *options.shutter;
    auto medium = buildMedium(shader, rec, pyro.bind, Transform(), scene.majorantResolution,
                              FileLoc{rec.file, 0, 0}, scene, options);
    // Its still bounds frame the camera: the blur may reach beyond them.
    float aspect = float(scene.settings.width) / float(scene.settings.height);
    scene.render.camera = frameBounds(medium->worldBounds(), 40.f, aspect);
    rec.velocity = findVelocity(rec.file, names, scene.shutter.blurs(), options.grids);
    try {
        medium->setMotion(volumeMotion(scene, KeyedTransform(), &rec));
    } catch (const MirageError& e) {
        throw MirageError(rec.file + ": " + e.what());
    }
    scene.render.media.push_back(std::move(medium));
    scene.volumes.push_back(rec);
    setShutterSeconds(&scene);
    // Key light from the camera's upper left, white in the working space (a D65 spectrum's
    // colour); a white diffuser facing it would read Y = 1.
    scene.render.lights.push_back(makeDistantLight(
        Vec3(1.f, -1.2f, -0.8f), kUnitWhiteIrradiance,
        rgbIlluminantSpectrum(Vec3(1.f, 1.f, 1.f), color.xyzToWorking())));
    bool pathSet = std::any_of(options.overrides.begin(), options.overrides.end(),
                               [](const std::string& o) { return o.rfind("output.path=", 0) == 0; });
    if (!pathSet) scene.output.path = (fs::path(rec.file).stem().string() + ".exr");
    useIntegrator(options, &scene);
    return scene;
}

}  // namespace mirage
