// [[material]] and [[shape]] tables. Keys (docs/scene-file.md, "Surfaces"):
//   material: name, type = diffuse | mirror | dielectric; diffuse: reflectance (number or RGB,
//             default 0.8), emission (radiance W·m⁻²·sr⁻¹·nm⁻¹, number or working-space RGB);
//             mirror: reflectance (default 1); dielectric: ior (A, default 1.5), cauchy_b (B in
//             µm², default 0: n(λ) = A + B/λ²).
//   shape:    type = mesh (file = OBJ) | sphere (center, radius) | quad (corner, edge_u,
//             edge_v); material (a [[material]] name); transform (as for volumes); holdout
//             (true: black with zero alpha to the camera, docs/aovs.md);
//             interior_medium (index of a [[volume]] placed inside a sphere or closed mesh:
//             the scene loader confines that medium to the shape's inside).
// Keys a type does not read are reported as unknown by TableReader::finish.
#include "scene/geometry_loader.h"

#include <algorithm>
#include <filesystem>

#include "core/path_check.h"
#include "core/text.h"
#include "film/color.h"
#include "scene/output_loader.h"

namespace mirage {

namespace {

// A number (grey) or an RGB triple: reflectance-like values by the smooth RGB basis, so that
// values in [0, 1] stay in [0, 1] at every wavelength.
Spectrum readReflectance(const TableReader& t, const std::string& key, float def) {
    if (!t.has(key)) {
        t.node(key);
        return Spectrum(def);
    }
    if (t.node(key)->is_number()) return Spectrum(float(t.getNumber(key, def, 0.0, 1.0)));
    Vec3 rgb = t.getVec3(key);
    if (!(rgb.x >= 0 && rgb.y >= 0 && rgb.z >= 0 && rgb.x <= 1 && rgb.y <= 1 && rgb.z <= 1))
        t.fail(key, "expected reflectances in [0, 1]");
    return rgbReflectanceSpectrum(rgb);
}

Spectrum readEmission(const TableReader& t, const ColorPipeline& color) {
    if (!t.has("emission")) return Spectrum(0.f);
    if (t.node("emission")->is_number())
        return Spectrum(float(t.getNumber("emission", 0.0, 0.0, 1e12)));
    Vec3 rgb = t.getVec3("emission");
    if (!(rgb.x >= 0 && rgb.y >= 0 && rgb.z >= 0))
        t.fail("emission", "expected non-negative RGB radiance");
    if (rgb.x + rgb.y + rgb.z == 0.f) return Spectrum(0.f);
    return rgbIlluminantSpectrum(rgb, color.xyzToWorking());
}

Material readMaterial(const TableReader& t, const ColorPipeline& color) {
    std::string name = t.getString("name");
    std::string type = t.getString("type");
    Material m;
    if (type == "diffuse") {
        m = Material::diffuse(name, readReflectance(t, "reflectance", 0.8f), readEmission(t, color));
    } else if (type == "mirror") {
        m = Material::mirror(name, readReflectance(t, "reflectance", 1.f));
    } else if (type == "dielectric") {
        float a = float(t.getNumber("ior", 1.5, 1.0, 4.0));
        float b = float(t.getNumber("cauchy_b", 0.0, 0.0, 1.0));
        m = Material::dielectric(name, a, b);
    } else {
        t.fail("type", "unknown material type '" + type + "'; expected diffuse, mirror or dielectric");
    }
    t.finish();
    return m;
}

// The triangles (3 corners each, world) of the shape just added, among the emitters when its
// material emits.
void addEmitter(std::vector<Vec3> corners, int material, const GeometryScene& geometry,
                EmissiveTriangles* emitters) {
    if (!geometry.material(material).emissive()) return;
    emitters->shapes.resize(geometry.shapeCount(), false);
    emitters->shapes.back() = true;
    emitters->emitter.insert(emitters->emitter.end(), corners.size() / 3, material);
    emitters->vertices.insert(emitters->vertices.end(), corners.begin(), corners.end());
}

}  // namespace

std::unique_ptr<GeometryScene> readGeometry(
    const TableReader& top, const std::function<std::string(const std::string&)>& resolve,
    size_t volumeCount, const ColorPipeline& color, EmissiveTriangles* emitters) {
    const std::vector<TableReader> materials = top.tables("material"), shapes = top.tables("shape");
    if (materials.empty() && shapes.empty()) return nullptr;  // no Embree device for media alone
    auto geometry = std::make_unique<GeometryScene>();
    std::vector<std::string> names;
    for (const auto& t : materials) {
        Material m = readMaterial(t, color);
        if (std::find(names.begin(), names.end(), m.name()) != names.end())
            t.fail("name", "a material named '" + m.name() + "' is already defined");
        names.push_back(m.name());
        geometry->addMaterial(std::move(m));
    }

    EmissiveTriangles unused;
    if (!emitters) emitters = &unused;
    for (size_t m = 0; m < geometry->materialCount(); ++m) {
        const Material& mat = geometry->material(int(m));
        emitters->radiance.push_back(mat.emissive() ? mat.emissionSpectrum() : Spectrum(0.f));
    }
    std::vector<int> interiors;  // volumes already placed inside a shape
    for (const auto& t : shapes) {
        std::string type = t.getString("type");
        std::string matName = t.getString("material");
        auto it = std::find(names.begin(), names.end(), matName);
        if (it == names.end()) {
            const std::string list = joinList(names);
            t.fail("material", "no [[material]] is named '" + matName + "'" +
                                   (list.empty() ? " (none is defined)" : "; defined: " + list));
        }
        int material = int(it - names.begin());
        int interior = -1;
        if (t.has("interior_medium")) {
            if (volumeCount == 0)
                t.fail("interior_medium", "the scene has no [[volume]] to place inside the shape");
            interior = int(t.getInt("interior_medium", 0, 0, int64_t(volumeCount) - 1));
            if (type == "quad")
                t.fail("interior_medium",
                       "a quad encloses no volume; a medium needs a sphere or a closed mesh");
            if (std::find(interiors.begin(), interiors.end(), interior) != interiors.end())
                t.fail("interior_medium", "volume " + std::to_string(interior) +
                                              " is already inside another shape");
            interiors.push_back(interior);
        }
        Transform xf;
        if (auto x = t.optionalTable("transform")) xf = readTransform(*x);

        if (type == "sphere") {
            Vec3 c = t.getVec3("center", Vec3(0.f));
            float r = float(t.getNumber("radius", 1.0, 1e-9, 1e9));
            // A sphere stays a sphere only under a similarity: equal column lengths.
            float s[3];
            for (int j = 0; j < 3; ++j)
                s[j] = float(std::sqrt(xf.linear(0, j) * xf.linear(0, j) +
                                       xf.linear(1, j) * xf.linear(1, j) +
                                       xf.linear(2, j) * xf.linear(2, j)));
            if (std::abs(s[0] - s[1]) > 1e-4f * s[0] || std::abs(s[0] - s[2]) > 1e-4f * s[0])
                t.fail("transform", "a sphere takes a uniform scale only");
            geometry->addSphere(xf.point(c), r * s[0], material, interior);
        } else if (type == "quad") {
            Vec3 corner = t.getVec3("corner"), u = t.getVec3("edge_u"), v = t.getVec3("edge_v");
            if (!(length(cross(u, v)) > 0.f))
                t.fail("edge_v", "the quad's edges are parallel or zero");
            geometry->addQuad(xf.point(corner), xf.vector(u), xf.vector(v), material, interior);
            const Vec3 c = xf.point(corner), cu = c + xf.vector(u), cv = c + xf.vector(v);
            addEmitter({c, cu, cu + xf.vector(v), c, cu + xf.vector(v), cv}, material, *geometry,
                       emitters);
        } else if (type == "mesh") {
            std::string file = resolve(t.getString("file"));
            if (const std::string problem = pathProblem(file); !problem.empty())
                t.fail("file", "mesh file " + problem + ": " + file);
            TriangleMesh mesh;
            try {
                mesh = loadObjMesh(file);
            } catch (const MirageError& e) {
                t.fail("file", e.what());
            }
            geometry->addMesh(mesh, xf, material, interior);
            std::vector<Vec3> corners;
            for (uint32_t i : mesh.indices) corners.push_back(xf.point(mesh.positions[i]));
            addEmitter(std::move(corners), material, *geometry, emitters);
        } else {
            t.fail("type", "unknown shape type '" + type + "'; expected mesh, sphere or quad");
        }
        const int shape = int(geometry->shapeCount()) - 1;
        emitters->shapes.resize(size_t(shape) + 1, false);
        geometry->setHoldout(shape, t.getBool("holdout", false));
        geometry->setName(shape, readObjectName(t, "shape" + std::to_string(shape)));
        t.finish();
    }
    if (geometry->empty()) return nullptr;
    geometry->commit();
    return geometry;
}

}  // namespace mirage
