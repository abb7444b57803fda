// OBJ → TriangleMesh with tinyobjloader (libtinyobjloader-dev). Every object and group of the
// file becomes one mesh (materials in the file are ignored: the scene file assigns one).
// tinyobjloader indexes positions and normals separately; Embree wants one index per vertex,
// so each distinct (position, normal) pair becomes a vertex.
#include <tiny_obj_loader.h>

#include <map>
#include <utility>

#include "core/error.h"
#include "geometry/geometry_scene.h"

namespace mirage {

TriangleMesh loadObjMesh(const std::string& path) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = "";
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string msg = reader.Error();
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == '\r')) msg.pop_back();
        throw MirageError(FileLoc{path, 0, 0}, "cannot read OBJ mesh: " +
                                                   boundedMessage(msg.empty() ? "unknown error" : msg));
    }
    const tinyobj::attrib_t& a = reader.GetAttrib();

    // Normals only when every face corner has one: a half-normalled mesh would shade in patches.
    bool haveNormals = !a.normals.empty();
    for (const auto& s : reader.GetShapes())
        for (const auto& i : s.mesh.indices) haveNormals &= i.normal_index >= 0;

    TriangleMesh mesh;
    std::map<std::pair<int, int>, uint32_t> vertexOf;
    for (const auto& s : reader.GetShapes()) {
        for (const auto& i : s.mesh.indices) {
            if (i.vertex_index < 0 || size_t(3 * i.vertex_index + 2) >= a.vertices.size())
                throw MirageError(FileLoc{path, 0, 0}, "OBJ face refers to a missing vertex");
            std::pair<int, int> key(i.vertex_index, haveNormals ? i.normal_index : -1);
            auto [it, inserted] = vertexOf.emplace(key, uint32_t(mesh.positions.size()));
            if (inserted) {
                const float* v = &a.vertices[3 * size_t(i.vertex_index)];
                mesh.positions.emplace_back(v[0], v[1], v[2]);
                if (haveNormals) {
                    const float* n = &a.normals[3 * size_t(i.normal_index)];
                    mesh.normals.emplace_back(n[0], n[1], n[2]);
                }
            }
            mesh.indices.push_back(it->second);
        }
    }
    if (mesh.indices.empty())
        throw MirageError(FileLoc{path, 0, 0}, "the OBJ file has no faces");
    return mesh;
}

}  // namespace mirage
