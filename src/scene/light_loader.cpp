// [[light]] tables → lights: point and spot (either with a radius: a sphere; either with an
// IES profile), distant/sun, quad and dome, coloured by RGB in the working space or by a
// blackbody temperature (docs/scene-file.md, "Lights").
#include "scene/light_loader.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "film/color.h"
#include "light/dome_light.h"
#include "light/ies_file.h"
#include "light/lamp.h"
#include "light/surface_light.h"
#include "scene/scene.h"
#include "spectrum/spectrum.h"

namespace mirage {

namespace {

Spectrum lightColour(const TableReader& t, const ColorPipeline& color) {
    if (t.has("temperature") && t.has("color"))
        t.fail("temperature", "give either 'color' or 'temperature', not both");
    if (t.has("temperature")) {
        double T = t.getNumber("temperature", 6500, 100, 1e6);
        return blackbodyNormalized(float(T));
    }
    Vec3 rgb = t.getVec3("color", Vec3(1, 1, 1));
    if (rgb.x < 0 || rgb.y < 0 || rgb.z < 0 || (rgb.x + rgb.y + rgb.z) <= 0)
        t.fail("color", "expected non-negative RGB values, not all zero");
    return rgbIlluminantSpectrum(rgb, color.xyzToWorking());
}

// A dome: a constant colour (color or temperature) times `intensity`, or an image `map` times
// `intensity`; `rotation` in degrees about +y; `camera_visible` (light/dome_light.h).
std::unique_ptr<Light> readDome(const TableReader& t, const ColorPipeline& color,
                                const std::function<std::string(const std::string&)>& resolve) {
    DomeSettings s;
    s.rotationDeg = float(t.getNumber("rotation", 0, -360, 360));
    s.cameraVisible = t.getBool("camera_visible", true);
    const float intensity = float(t.getNumber("intensity", 1, 0, 1e15));
    if (!t.has("map")) return makeDomeLight(lightColour(t, color).scaled(intensity), s);
    if (t.has("color") || t.has("temperature"))
        t.fail("map", "a dome takes either an image 'map' or a 'color'/'temperature', not both");
    const std::string file = resolve(t.getString("map"));
    try {
        return makeDomeLight(readLatLongImage(file), intensity, color.xyzToWorking(), s, file);
    } catch (const MirageError& e) {
        t.fail("map", e.what());
    }
    return nullptr;
}

// Where a lamp points: `look_at` or `direction`; `fallback` when neither is given (a spot must
// give one: fallback null).
Vec3 lampAxis(const TableReader& t, const Vec3& position, const Vec3* fallback) {
    if (fallback && !t.has("look_at") && !t.has("direction")) return *fallback;
    const Vec3 dir = t.has("look_at") ? t.getVec3("look_at") - position : t.getVec3("direction");
    if (!(length(dir) > 0))
        t.fail(t.has("look_at") ? "look_at" : "direction", "the light points nowhere");
    return normalize(dir);
}

// A point or spot light: position, power, colour; `radius` makes it a sphere; a spot's cone
// (cone_angle, cone_inner); `ies`, a photometric file shaping its intensity, its nadir along
// the spot's direction or a point light's `direction`/`look_at` (default straight down, −y).
std::unique_ptr<Light> readLamp(const TableReader& t, bool spot, const ColorPipeline& color,
                                const std::function<std::string(const std::string&)>& resolve) {
    LampDesc d;
    d.position = t.getVec3("position");
    d.powerW = float(t.getNumber("power", 100, 0, 1e15));
    d.radius = float(t.getNumber("radius", 0, 0, 1e6));
    const Vec3 down(0.f, -1.f, 0.f);
    if (spot) {
        d.profile.axis = lampAxis(t, d.position, nullptr);
        d.profile.spot = true;
        d.profile.outerDeg = float(t.getNumber("cone_angle", 30, 0.1, 180));
        d.profile.innerDeg =
            float(t.getNumber("cone_inner", d.profile.outerDeg * 0.8, 0, d.profile.outerDeg));
    }
    if (t.has("ies")) {
        if (!spot) d.profile.axis = lampAxis(t, d.position, &down);
        const std::string file = resolve(t.getString("ies"));
        try {
            d.profile.ies = std::make_shared<const IesProfile>(IesProfile::read(file));
        } catch (const MirageError& e) {
            t.fail("ies", e.what());
        }
    }
    return makeLamp(d, lightColour(t, color));
}

// [[light]] group: a name the lightgroup_<name> pass takes, so Nuke's layer rule applies.
std::string readLightGroup(const TableReader& l) {
    const std::string group = l.getString("group", "");
    if (!l.has("group")) return group;
    const bool valid = !group.empty() && std::all_of(group.begin(), group.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!valid)
        l.fail("group",
               "'" + group +
                   "': expected letters, digits and underscores (the pass "
                   "is named lightgroup_<group>, and a compositor splits layer names there)");
    if (group == "emission")
        l.fail("group",
               "'emission' is the group of light emitted by media and surfaces "
               "(lightgroup_emission); choose another name");
    return group;
}

// The light just added joins `group` ("" = "default"). Until a light names a group, every
// light is in "default" implicitly (RenderScene::lightGroupNames).
void assignLightGroup(const std::string& group, RenderScene* scene) {
    const size_t light = scene->lights.size() - 1;
    if (group.empty() && scene->lightGroups.empty()) return;
    if (scene->lightGroups.empty()) {
        // The first named group: the lights before it were in "default".
        if (light > 0) scene->lightGroups.push_back("default");
        scene->lightGroupIndex.assign(light, 0);
    }
    const std::string name = group.empty() ? "default" : group;
    auto it = std::find(scene->lightGroups.begin(), scene->lightGroups.end(), name);
    if (it == scene->lightGroups.end()) it = scene->lightGroups.insert(it, name);
    scene->lightGroupIndex.push_back(int(it - scene->lightGroups.begin()));
}

}  // namespace

std::unique_ptr<Light> readLight(const TableReader& t, const ColorPipeline& color,
                                 const std::function<std::string(const std::string&)>& resolve) {
    std::string type = t.getString("type");
    std::unique_ptr<Light> light;
    if (type == "point" || type == "spot") {
        light = readLamp(t, type == "spot", color, resolve);
    } else if (type == "distant" || type == "sun") {
        Vec3 dir = t.getVec3("direction");
        if (!(length(dir) > 0)) t.fail("direction", "expected a non-zero direction");
        light =
            makeDistantLight(dir, float(t.getNumber("irradiance", kUnitWhiteIrradiance, 0, 1e15)),
                             lightColour(t, color));
    } else if (type == "quad") {
        light = makeQuadLight(t.getVec3("corner"), t.getVec3("edge_u"), t.getVec3("edge_v"),
                              float(t.getNumber("power", 100, 0, 1e15)), lightColour(t, color));
    } else if (type == "dome") {
        light = readDome(t, color, resolve);
    } else {
        t.fail("type", "unknown light type '" + type +
                           "'; expected point, spot, distant, sun, quad or dome");
    }
    t.finish();
    return light;
}

void addSurfaceLight(EmissiveTriangles triangles, RenderScene* scene) {
    if (triangles.emitter.empty()) return;
    auto light = std::make_unique<SurfaceLight>(std::move(triangles));
    if (!(light->emittedPower(Bounds3{}) > 0.f)) return;
    scene->lights.push_back(std::move(light));
    // Its light is emission's (slot 0 of the light-group passes): lightGroupSlot adds 1.
    if (scene->lightGroupIndex.empty()) scene->lightGroupIndex.assign(scene->lights.size() - 1, 0);
    scene->lightGroupIndex.push_back(-1);
}

void readLights(const TableReader& top, const ColorPipeline& color,
                const std::function<std::string(const std::string&)>& resolve, RenderScene* scene) {
    for (const auto& l : top.tables("light")) {
        const std::string group = readLightGroup(l);
        scene->lights.push_back(readLight(l, color, resolve));
        assignLightGroup(group, scene);
    }
}

}  // namespace mirage
