"""Blender meshes as Mirage surfaces (docs/scene-file.md, "Surfaces"; docs/blender.md).

Geometry. The evaluated mesh (modifiers applied) is triangulated by Blender's own loop
triangles and written as an OBJ file in the export's folder, its points taken through the
object's world matrix M and then the Z-up to Y-up rotation C (units.py): Mirage reads the OBJ's
coordinates as its world, so they are C·M·p and the shape needs no transform. Each corner
carries Blender's split normal (smooth faces interpolate, flat and sharp-edged ones do not),
turned by the normal matrix C·(M⁻¹)ᵀ. A mirroring M (negative determinant) reverses the
triangles' winding to keep their geometric normals outward.

Materials. Mirage's surfaces are diffuse (Lambert), perfect mirrors and smooth dielectrics
(glass); the Principled BSDF's lobes are mapped to the nearest one:
    Transmission ≥ 0.5                      → dielectric of Cauchy A = IOR (no dispersion);
    Metallic ≥ 0.5 and Roughness ≤ 0.1      → mirror of reflectance Base Color;
    otherwise                               → diffuse of reflectance Base Color.
What that drops (a rough metal's gloss, a diffuse surface's specular coat, Subsurface,
Sheen, Clearcoat, Emission, textures linked into the inputs) is named in the material
warning. A Holdout node in the Surface socket, or the object's Visibility › Holdout, makes
the shape a `holdout` (docs/aovs.md, "Holdouts").
"""
import hashlib
import os

import numpy as np

from . import shading, units

_GEOMETRY = ("MESH", "CURVE", "SURFACE", "META", "FONT")
# A Principled BSDF above these is Mirage's glass or mirror (module docstring).
_TRANSMISSIVE = 0.5
_METALLIC = 0.5
_SMOOTH = 0.1
# Principled inputs Mirage's three surfaces have no term for, with the value that means "off".
_DROPPED = (("Subsurface", 0.0), ("Sheen", 0.0), ("Clearcoat", 0.0))


def is_geometry(obj):
    return obj.type in _GEOMETRY


def _obj_text(points, normals, triangles):
    """The OBJ file: one vertex and one normal per triangle corner, faces `f a//a b//b c//c`."""
    corners = np.arange(1, len(triangles) * 3 + 1).reshape(-1, 3)
    faces = np.repeat(corners, 2, axis=1)
    lines = ["# Mirage export of a Blender mesh: world coordinates, Y up, metres"]
    lines += ["v %.9g %.9g %.9g" % tuple(p) for p in points]
    lines += ["vn %.9g %.9g %.9g" % tuple(n) for n in normals]
    lines += ["f %d//%d %d//%d %d//%d" % tuple(f) for f in faces]
    return "\n".join(lines) + "\n"


def _world_triangles(obj):
    """The evaluated mesh's triangle corners (points, normals: (3·T, 3) arrays) in Mirage's
    world, or None when it has no faces."""
    mesh = obj.to_mesh()
    try:
        mesh.calc_loop_triangles()
        count = len(mesh.loop_triangles)
        if count == 0:
            return None
        mesh.calc_normals_split()
        co = np.empty(len(mesh.vertices) * 3, dtype=np.float64)
        mesh.vertices.foreach_get("co", co)
        index = np.empty(count * 3, dtype=np.int64)
        mesh.loop_triangles.foreach_get("vertices", index)
        normals = np.empty(count * 9, dtype=np.float64)
        mesh.loop_triangles.foreach_get("split_normals", normals)
    finally:
        obj.to_mesh_clear()
    m = np.array(obj.matrix_world, dtype=np.float64)
    axes = np.array(units.AXES, dtype=np.float64)
    points = co.reshape(-1, 3)[index] @ (axes @ m[:3, :3]).T + axes @ m[:3, 3]
    normal_matrix = axes @ np.linalg.inv(m[:3, :3]).T
    normals = normals.reshape(-1, 3) @ normal_matrix.T
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-30)
    if np.linalg.det(m[:3, :3]) < 0.0:
        order = np.arange(count * 3).reshape(-1, 3)[:, [0, 2, 1]].ravel()
        points, normals = points[order], normals[order]
    return points, normals, np.arange(count)


def _write_obj(obj, folder, safe_name):
    """The object's OBJ file in `folder`, named by its content (an edited mesh is a new file),
    or None for a mesh without faces."""
    tri = _world_triangles(obj)
    if tri is None:
        return None
    text = _obj_text(*tri)
    digest = hashlib.sha1(text.encode()).hexdigest()[:10]
    path = os.path.join(folder, f"mesh_{safe_name}_{digest}.obj")
    os.makedirs(folder, exist_ok=True)
    if not os.path.exists(path):
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
    return path


def _principled(node, left_out):
    """A Principled BSDF as Mirage's nearest surface (module docstring)."""
    value = lambda socket: shading.value(node, socket, left_out)  # noqa: E731
    base = shading.rgb(value("Base Color"))
    if float(value("Transmission")) >= _TRANSMISSIVE:
        if float(value("Roughness")) > _SMOOTH:
            left_out.append(f"{node.name} › Roughness (Mirage's glass is smooth)")
        return {"type": "dielectric", "ior": min(max(float(value("IOR")), 1.0), 4.0)}
    for socket, off in _DROPPED:
        if float(value(socket)) != off:
            left_out.append(f"{node.name} › {socket}")
    if float(value("Emission Strength")) > 0.0 and max(shading.rgb(value("Emission"))) > 0.0:
        left_out.append(f"{node.name} › Emission")
    if float(value("Metallic")) >= _METALLIC:
        if float(value("Roughness")) <= _SMOOTH:
            return {"type": "mirror", "reflectance": [min(c, 1.0) for c in base]}
        left_out.append(f"{node.name} › rough Metallic (rendered diffuse)")
    return {"type": "diffuse", "reflectance": [min(c, 1.0) for c in base]}


def _node_material(node, left_out):
    """The surface a Surface socket's node becomes; None for a Holdout node."""
    kind = node.bl_idname
    if kind == "ShaderNodeHoldout":
        return None
    if kind == "ShaderNodeBsdfPrincipled":
        return _principled(node, left_out)
    if kind == "ShaderNodeBsdfDiffuse":
        color = shading.rgb(shading.value(node, "Color", left_out))
        return {"type": "diffuse", "reflectance": [min(c, 1.0) for c in color]}
    if kind == "ShaderNodeBsdfGlass":
        ior = float(shading.value(node, "IOR", left_out))
        return {"type": "dielectric", "ior": min(max(ior, 1.0), 4.0)}
    left_out.append(f"{node.name} (rendered as a grey diffuse surface)")
    return {"type": "diffuse", "reflectance": 0.8}


def material(mat, left_out):
    """(the [[material]] table without its name, holdout) for a Blender material; a material
    without nodes is its viewport Base Color as diffuse."""
    if mat is None:
        return {"type": "diffuse", "reflectance": 0.8}, False
    if not mat.use_nodes or mat.node_tree is None:
        return {"type": "diffuse", "reflectance": shading.rgb(mat.diffuse_color)}, False
    node = shading.output_node(mat.node_tree, "Surface")
    if node is None:
        return {"type": "diffuse", "reflectance": 0.8}, False
    table = _node_material(node, left_out)
    if table is None:
        return {"type": "diffuse", "reflectance": 0.0}, True
    return table, False


class Surfaces:
    """The export's [[material]] and [[shape]] tables: one material per Blender material."""

    def __init__(self):
        self.materials = {}   # Mirage material name -> table
        self.shapes = []

    def add(self, obj, folder, safe_name, ex):
        """A mesh-like object as a [[shape]] reading its OBJ file (module docstring)."""
        path = _write_obj(obj, folder, safe_name(obj.name))
        if path is None:
            return
        mat = obj.active_material
        notes = []
        table, holdout = material(mat, notes)
        ex.left_out_nodes += [f"{mat.name}: {n}" for n in notes]
        name = safe_name(mat.name) if mat is not None else "default"
        self.materials.setdefault(name, {"name": name, **table})
        shape = {"type": "mesh", "file": path, "material": name, "name": safe_name(obj.name)}
        if holdout or obj.is_holdout:
            shape["holdout"] = True
        self.shapes.append(shape)

    def into(self, doc):
        if self.shapes:
            doc["material"] = list(self.materials.values())
            doc["shape"] = self.shapes
