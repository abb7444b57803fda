// The Embree surface scene: analytic spheres from outside and inside, quads, OBJ meshes,
// occlusion, and the scene file's [[material]] / [[shape]] tables with their errors.
#include "geometry/geometry_scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include <fstream>

#include "core/error.h"
#include "film/color.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace mirage;

namespace {

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
    std::string p = dir + "/" + name;
    std::ofstream(p) << text;
    return p;
}

std::string loadError(const std::string& path) {
    ColorPipeline color;
    try {
        loadScene(path, LoadOptions{}, color);
    } catch (const MirageError& e) {
        return e.what();
    }
    return "";
}

// A unit cube [0, 1]³ as an OBJ with outward counter-clockwise faces (quads, triangulated).
const char* kCubeObj = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 3 4 8 7
f 2 3 7 6
f 1 5 8 4
)";

}  // namespace

TEST(GeometryScene, SphereFromOutsideAndInside) {
    GeometryScene g;
    int m = g.addMaterial(Material::diffuse("white", Spectrum(0.5f)));
    g.addSphere(Vec3(1, 2, 3), 0.5f, m);
    g.commit();
    auto h = g.intersect(Ray{Vec3(1, 2, -2), Vec3(0, 0, 1), kInfinity});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 4.5f, 1e-5f);
    EXPECT_NEAR(h->ng.z, -1.f, 1e-5f);  // outward
    EXPECT_EQ(h->material, m);
    auto in = g.intersect(Ray{Vec3(1, 2, 3), normalize(Vec3(1, 1, 0)), kInfinity});
    ASSERT_TRUE(in);
    EXPECT_NEAR(in->t, 0.5f, 1e-5f);
    EXPECT_GT(dot(in->ng, Vec3(1, 1, 0)), 0.f);
    EXPECT_FALSE(g.intersect(Ray{Vec3(1, 2, -2), Vec3(0, 0, 1), 4.f}));  // tMax short of it
    EXPECT_FALSE(g.intersect(Ray{Vec3(2, 2, -2), Vec3(0, 0, 1), kInfinity}));
    // A ray spawned off the surface does not hit it again on the way out.
    auto out = g.intersect(spawnRay(*h, Vec3(0, 0, -1)));
    EXPECT_FALSE(out);
    auto through = g.intersect(spawnRay(*h, Vec3(0, 0, 1)));
    ASSERT_TRUE(through);
    EXPECT_NEAR(through->t, 1.f, 1e-4f);
    EXPECT_TRUE(g.occluded(Vec3(1, 2, -2), Vec3(0, 0, 1), 10.f));
    EXPECT_FALSE(g.occluded(Vec3(1, 2, -2), Vec3(0, 0, 1), 4.f));
}

// A ray with a NaN direction (a curved path gone wrong) meets nothing instead of tripping
// Embree's assertion, which aborts the process.
TEST(GeometryScene, NonFiniteRaysMeetNothing) {
    GeometryScene g;
    g.addSphere(Vec3(0, 0, 0), 1.f, g.addMaterial(Material::diffuse("white", Spectrum(0.5f))));
    g.commit();
    const float nan = std::nanf("");
    EXPECT_FALSE(g.intersect(Ray{Vec3(0, 0, -5), Vec3(nan, nan, nan), kInfinity}));
    EXPECT_FALSE(g.intersect(Ray{Vec3(nan, 0, -5), Vec3(0, 0, 1), kInfinity}));
    EXPECT_TRUE(std::isinf(g.surfaceDistance(Vec3d(0, 0, -5), Vec3d(std::nan(""), 0, 0))));
    EXPECT_TRUE(g.intersect(Ray{Vec3(0, 0, -5), Vec3(0, 0, 1), kInfinity}));
}

TEST(GeometryScene, QuadNormalAndEdges) {
    GeometryScene g;
    int m = g.addMaterial(Material::mirror("m"));
    g.addQuad(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, -1), m);  // y = 0, normal +y
    g.commit();
    auto h = g.intersect(Ray{Vec3(1.5f, 1, -0.9f), Vec3(0, -1, 0), kInfinity});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 1.f, 1e-6f);
    EXPECT_NEAR(h->ng.y, 1.f, 1e-6f);
    EXPECT_FALSE(g.intersect(Ray{Vec3(2.1f, 1, -0.5f), Vec3(0, -1, 0), kInfinity}));
    EXPECT_FALSE(g.intersect(Ray{Vec3(1, 1, 0.1f), Vec3(0, -1, 0), kInfinity}));
    EXPECT_NEAR(g.bounds().hi.x, 2.f, 1e-6f);
}

TEST(GeometryScene, ObjMeshWithTransform) {
    std::string dir = test::tempDir();
    std::string obj = writeFile(dir, "cube.obj", kCubeObj);
    TriangleMesh mesh = loadObjMesh(obj);
    EXPECT_EQ(mesh.indices.size(), 36u);
    GeometryScene g;
    int m = g.addMaterial(Material::diffuse("d", Spectrum(0.5f)));
    Transform xf = Transform::translate(Vec3d(10, 0, 0)) * Transform::scale(Vec3d(2, 2, 2));
    g.addMesh(mesh, xf, m);
    g.commit();
    EXPECT_EQ(g.shape(0).triangles, 12u);
    auto h = g.intersect(Ray{Vec3(11, 1, -5), Vec3(0, 0, 1), kInfinity});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 5.f, 1e-5f);
    EXPECT_NEAR(h->ng.z, -1.f, 1e-5f);  // outward face
    auto inside = g.intersect(Ray{Vec3(11, 1, 1), Vec3(1, 0, 0), kInfinity});
    ASSERT_TRUE(inside);
    EXPECT_NEAR(inside->t, 1.f, 1e-5f);
    EXPECT_NEAR(inside->ng.x, 1.f, 1e-5f);

    EXPECT_THROW(loadObjMesh(writeFile(dir, "bad.obj", "v 0 0 0\nf 1 2 3\n")), MirageError);
}

TEST(GeometryScene, SceneFileMaterialsAndShapes) {
    std::string dir = test::tempDir();
    writeFile(dir, "cube.obj", kCubeObj);
    std::string ok = writeFile(dir, "ok.toml", R"(
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]

[[material]]
name = "white"
type = "diffuse"
reflectance = [0.8, 0.7, 0.6]
emission = 0.5

[[material]]
name = "glass"
type = "dielectric"
ior = 1.5
cauchy_b = 0.004

[[shape]]
type = "sphere"
center = [0, 0, 0]
radius = 0.5
material = "glass"

[[shape]]
type = "quad"
corner = [-1, -1, -1]
edge_u = [2, 0, 0]
edge_v = [0, 0, 2]
material = "white"

[[shape]]
type = "mesh"
file = "cube.obj"
material = "white"
transform = { scale = 0.5, translate = [2, 0, 0] }
)");
    ColorPipeline color;
    Scene s = loadScene(ok, LoadOptions{}, color);
    ASSERT_TRUE(s.render.hasSurfaces());
    const GeometryScene& g = *s.render.geometry;
    EXPECT_EQ(g.shapeCount(), 3u);
    EXPECT_EQ(g.materialCount(), 2u);
    EXPECT_TRUE(g.material(1).dispersive());
    EXPECT_TRUE(g.material(0).emissive());
    EXPECT_NEAR(g.bounds().hi.x, 2.5f, 1e-5f);
    bool surfaces = false;
    for (const auto& t : s.physics())
        if (t.name == "surfaces") surfaces = t.active;
    EXPECT_TRUE(surfaces);

    // Errors name the file, line and column.
    std::string e = loadError(writeFile(dir, "unknown.toml", R"([[material]]
name = "m"
type = "mirror"
ior = 1.5
)"));
    EXPECT_NE(e.find("unknown.toml:4:"), std::string::npos) << e;
    EXPECT_NE(e.find("ior"), std::string::npos) << e;
    e = loadError(writeFile(dir, "nomat.toml", R"([[material]]
name = "m"
type = "diffuse"
[[shape]]
type = "sphere"
radius = 1
material = "gold"
)"));
    EXPECT_NE(e.find("nomat.toml:7:"), std::string::npos) << e;
    EXPECT_NE(e.find("gold"), std::string::npos) << e;
    e = loadError(writeFile(dir, "type.toml", R"([[material]]
name = "m"
type = "diffuse"
reflectance = "white"
)"));
    EXPECT_NE(e.find("type.toml:4:"), std::string::npos) << e;
    e = loadError(writeFile(dir, "nofile.toml", R"([[material]]
name = "m"
type = "diffuse"
[[shape]]
type = "mesh"
file = "missing.obj"
material = "m"
)"));
    EXPECT_NE(e.find("missing.obj"), std::string::npos) << e;
    e = loadError(writeFile(dir, "medium.toml", R"([[material]]
name = "m"
type = "dielectric"
[[shape]]
type = "sphere"
material = "m"
interior_medium = 0
)"));
    EXPECT_NE(e.find("interior_medium"), std::string::npos) << e;
}
