"""A Blender scene as a Mirage scene document: the dict that mirage.Scene.from_dict takes, with
exactly the scene file's keys (docs/scene-file.md), and the shader files its volumes name.
One function per kind: film, camera, lights, world, volumes, surfaces (surfaces.py;
docs/blender.md, "What is translated"). Everything that cannot be translated is named, once, in the export's notes.
"""
import hashlib
import math
import os
import re

import bpy
from mathutils import Vector

from . import mantaflow, motion, physics, shading, surfaces, toml_text, units

# The add-on's OCIO config: Mirage's working space is Blender's scene-linear (units.py).
OCIO_CONFIG = os.path.join(os.path.dirname(__file__), "ocio", "config.ocio")


class ExportError(Exception):
    """What stops a render before Mirage sees it (a missing cache file): one message."""


class Export:
    """The scene document, its shaders, and what was left out of the translation."""

    def __init__(self, folder):
        self.folder = folder
        self.scene = {}
        self.shaders = {}          # file name -> shader document
        self.left_out_nodes = []   # "Material: node" entries, for the one material warning
        self.left_out = []         # other settings that Mirage does not take
        self.materials = []        # (material, shader, table) of each [[volume]], in order

    def write_shaders(self):
        """Writes each shader file into the export's folder (the scene names them by path)."""
        os.makedirs(self.folder, exist_ok=True)
        for name, doc in self.shaders.items():
            with open(os.path.join(self.folder, name), "w", encoding="utf-8") as f:
                f.write(toml_text.dumps(doc))

    def write_scene(self, path):
        """The scene as a TOML file that `mirage render --ocio <OCIO_CONFIG>` renders."""
        self.write_shaders()
        with open(path, "w", encoding="utf-8") as f:
            f.write(toml_text.dumps(self.scene))


def _safe_name(name):
    """A Blender name as Mirage takes names (Cryptomatte's: letters, digits and _ - . / :)."""
    return re.sub(r"[^A-Za-z0-9_\-./:]", "_", name) or "unnamed"


def resolution(scene):
    r = scene.render
    return (max(1, r.resolution_x * r.resolution_percentage // 100),
            max(1, r.resolution_y * r.resolution_percentage // 100))


def film(scene, settings):
    w, h = resolution(scene)
    return {"resolution": [w, h], "spp": int(settings.samples), "seed": int(settings.seed)}


def camera(scene, ex):
    """The active camera: position, look-at and up from its world matrix (a Blender camera
    looks along its local -Z with +Y up), and Mirage's vertical field of view from the focal
    length, the sensor and its fit."""
    cam_obj = scene.camera
    if cam_obj is None:
        raise ExportError("the scene has no active camera")
    cam = cam_obj.data
    w, h = resolution(scene)
    aspect = (w * scene.render.pixel_aspect_x) / (h * scene.render.pixel_aspect_y)
    fit = cam.sensor_fit
    if fit == "AUTO":
        fit = "HORIZONTAL" if aspect >= 1.0 else "VERTICAL"
        size = cam.sensor_width
    else:
        size = cam.sensor_width if fit == "HORIZONTAL" else cam.sensor_height
    tan_half = size / (2.0 * cam.lens)
    if fit == "HORIZONTAL":
        tan_half /= aspect
    if cam.type != "PERSP":
        ex.left_out.append(f"camera '{cam_obj.name}': type {cam.type} (rendered as perspective)")
    if cam.shift_x or cam.shift_y:
        ex.left_out.append(f"camera '{cam_obj.name}': lens shift")
    if cam.dof.use_dof:
        ex.left_out.append(f"camera '{cam_obj.name}': depth of field")
    return camera_from_matrix(cam_obj.matrix_world, tan_half)


def camera_from_matrix(m, tan_half):
    """Mirage's [camera] for a camera-to-world matrix (looking along its local -Z, +Y up, as
    Blender's cameras and viewports do) whose vertical half-angle has tangent `tan_half`."""
    pos = m.translation
    forward = (m.to_3x3() @ Vector((0.0, 0.0, -1.0))).normalized()
    up = (m.to_3x3() @ Vector((0.0, 1.0, 0.0))).normalized()
    return {"position": units.to_mirage(pos), "look_at": units.to_mirage(pos + forward),
            "up": units.to_mirage(up), "fov": math.degrees(2.0 * math.atan(tan_half))}


def _direction(obj):
    """Where a light shines: its local -Z in the world, in Mirage's axes."""
    return units.to_mirage((obj.matrix_world.to_3x3() @ Vector((0.0, 0.0, -1.0))).normalized())


def light(obj, ex):
    """A Blender light as a Mirage [[light]] table (units.py), or None with a note."""
    lamp = obj.data
    color = list(lamp.color)
    if lamp.type == "SUN":
        if lamp.angle > math.radians(1.0):
            ex.left_out.append(f"light '{obj.name}': sun angle (a delta light in Mirage)")
        return {"type": "sun", "direction": _direction(obj), "color": color,
                "irradiance": units.sun_irradiance(lamp.energy, color)}
    pos = units.to_mirage(obj.matrix_world.translation)
    # Cycles' point and spot lights are spheres of radius shadow_soft_size (metres, the
    # object's scale left out, as Cycles does), and so are Mirage's with `radius`.
    radius = {"radius": float(lamp.shadow_soft_size)} if lamp.shadow_soft_size > 0.0 else {}
    if lamp.type == "POINT":
        return {"type": "point", "position": pos, "color": color,
                "power": units.point_power(lamp.energy, color), **radius}
    if lamp.type == "SPOT":
        outer, inner = units.spot_cone(lamp.spot_size, lamp.spot_blend)
        power = units.spot_power(lamp.energy, color, math.cos(math.radians(inner)),
                                 math.cos(math.radians(outer)))
        return {"type": "spot", "position": pos, "direction": _direction(obj), "color": color,
                "cone_angle": outer, "cone_inner": inner, "power": power, **radius}
    if lamp.type == "AREA":
        return _area(obj, lamp, color, ex)
    ex.left_out.append(f"light '{obj.name}': type {lamp.type}")
    return None


def _area(obj, lamp, color, ex):
    """An area light as a quad centred on the object, emitting along its local -Z (a disc or
    ellipse as the rectangle of its size). Cycles' power does not change with the size or the
    object's scale, nor does Mirage's."""
    sx = lamp.size
    sy = lamp.size_y if lamp.shape in ("RECTANGLE", "ELLIPSE") else lamp.size
    if lamp.shape in ("DISK", "ELLIPSE"):
        ex.left_out.append(f"light '{obj.name}': {lamp.shape.lower()} shape (a rectangle)")
    m3 = obj.matrix_world.to_3x3()
    # Local +X, then -Y: their cross product is local -Z, the side Blender's area light lights.
    u = m3 @ Vector((sx, 0.0, 0.0))
    v = m3 @ Vector((0.0, -sy, 0.0))
    corner = obj.matrix_world.translation - 0.5 * u - 0.5 * v
    return {"type": "quad", "corner": units.to_mirage(corner), "edge_u": units.to_mirage(u),
            "edge_v": units.to_mirage(v), "color": color,
            "power": units.area_power(lamp.energy, color)}


def world(scene, ex):
    """The world's Background as a Mirage dome: a constant colour × strength (radiance, which
    Mirage's dome takes as RGB), or an equirectangular Environment Texture with the Z rotation
    of a Mapping node in front of it. None for a black world."""
    w = scene.world
    if w is None:
        return None
    if not w.use_nodes:
        c = list(w.color)
        return {"type": "dome", "color": c} if sum(c) > 0 else None
    tree = w.node_tree
    outs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputWorld"]
    out = next((n for n in outs if n.is_active_output), outs[0] if outs else None)
    if out is None or not out.inputs["Surface"].is_linked:
        return None
    bg = out.inputs["Surface"].links[0].from_node
    if bg.bl_idname != "ShaderNodeBackground":
        ex.left_out.append(f"world '{w.name}': {bg.name} (only a Background node)")
        return None
    strength = float(bg.inputs["Strength"].default_value)
    camera_visible = not scene.render.film_transparent
    col = bg.inputs["Color"]
    if col.is_linked:
        return _environment(col.links[0].from_node, strength, camera_visible, w, ex)
    c = [max(float(x), 0.0) for x in col.default_value[:3]]
    if strength <= 0.0 or sum(c) <= 0.0:
        return None
    return {"type": "dome", "color": c, "intensity": strength, "camera_visible": camera_visible}


def _environment(tex, strength, camera_visible, w, ex):
    if tex.bl_idname != "ShaderNodeTexEnvironment" or tex.image is None:
        ex.left_out.append(f"world '{w.name}': {tex.name} (only an Environment Texture)")
        return None
    if tex.projection != "EQUIRECTANGULAR":
        ex.left_out.append(f"world '{w.name}': {tex.name} projection {tex.projection}")
    path = bpy.path.abspath(tex.image.filepath, library=tex.image.library)
    if tex.image.packed_file is not None or not os.path.isfile(path):
        raise ExportError(f"world '{w.name}': environment image '{tex.image.name}' has no file "
                          f"on disk ({path or 'packed or generated'})")
    rotation = 0.0
    vec = tex.inputs["Vector"]
    if vec.is_linked:
        mapping = vec.links[0].from_node
        if mapping.bl_idname == "ShaderNodeMapping":
            rot = mapping.inputs["Rotation"].default_value
            if abs(rot[0]) > 1e-6 or abs(rot[1]) > 1e-6:
                ex.left_out.append(f"world '{w.name}': {mapping.name} X and Y rotation")
            rotation = rot[2]
        else:
            ex.left_out.append(f"world '{w.name}': {mapping.name}")
    return {"type": "dome", "map": os.path.abspath(path), "intensity": strength,
            "rotation": units.dome_rotation(rotation), "camera_visible": camera_visible}


def volume_frame_path(vol, frame):
    """The file a Volume datablock reads at `frame`: Blender's rule for sequences (frame
    start, duration, mode, then the offset), written into the file name's last number with
    its padding. None where the sequence has no frame (the Clip mode outside its range)."""
    path = bpy.path.abspath(vol.filepath, library=vol.library)
    if not vol.is_sequence:
        return path
    n, duration = frame - vol.frame_start + 1, vol.frame_duration
    if duration <= 0:
        return None
    mode = vol.sequence_mode
    if mode == "CLIP" and not 1 <= n <= duration:
        return None
    if mode == "EXTEND":
        n = min(max(n, 1), duration)
    elif mode == "REPEAT":
        n = n % duration or duration
    elif mode == "PING_PONG":
        period = max(duration * 2 - 2, 1)
        n = n % period or period
        n = duration * 2 - n if n > duration else n
    n += vol.frame_offset
    head, tail = os.path.split(path)
    m = list(re.finditer(r"\d+", tail))
    if not m:
        return path
    last = m[-1]
    digits = str(n).zfill(len(last.group()))
    return os.path.join(head, tail[:last.start()] + digits + tail[last.end():])


def transform(matrix):
    """A file-to-Blender-world matrix M as Mirage's scale, rotate, translate (S, then R, then
    T). Mirage reads the file's coordinates as its own, so its transform must be C·M, C the
    Z-up to Y-up rotation (units.py): C·M·p = C·t + (C·R)·S·p, a rotation C·R, not C·R·C⁻¹."""
    loc, rot, scale = matrix.decompose()
    axis, angle = (units.AXES @ rot.to_matrix()).to_quaternion().to_axis_angle()
    return {"scale": [float(s) for s in scale],
            "rotate": [math.degrees(angle)] + [float(a) for a in axis],
            "translate": units.to_mirage(loc)}


def _object_space_density(obj):
    """Blender's volume density is per unit of object space by default (Volume › Render ›
    Space: Object, "opacity the same regardless of object scale"): Cycles multiplies it by
    1 / |M (1, 1, 1) / sqrt 3|, one scale for every direction. Mirage's sigma is per metre of
    the world, so the same factor goes into density_scale; Space: World needs none."""
    if obj.data.render.space != "OBJECT":
        return 1.0
    diagonal = obj.matrix_world.to_3x3() @ Vector((1.0, 1.0, 1.0)).normalized()
    return 1.0 / diagonal.length if diagonal.length > 0.0 else 1.0


def require_file(obj, path, frame):
    if not os.path.isfile(path):
        raise ExportError(f"volume '{obj.name}': cache file {os.path.abspath(path)} does not exist "
                          f"(frame {frame})")


def volume(obj, frame, ex):
    """A Volume object: its frame's OpenVDB file, its transform, its material's shader."""
    vol = obj.data
    path = volume_frame_path(vol, frame)
    if path is None:
        return None
    require_file(obj, path, frame)
    grids = set()
    if vol.grids.load():
        grids = {g.name for g in vol.grids}
    return volume_table(obj, path, grids, {}, transform(obj.matrix_world),
                        _object_space_density(obj), ex)


def volume_table(obj, path, grids, renames, file_transform, density_factor, ex):
    """The [[volume]] of an object reading `path`: its material's shader (written into the
    export), the shader's attributes bound to the file's grids (`renames`: an attribute the
    file stores under another name), the transform and the density's factor."""
    mat = obj.active_material
    shader = shading.translate(mat, grids, _safe_name(mat.name if mat else "default"))
    physics.add_to_shader(mat, shader, density_factor)
    ex.left_out_nodes += [f"{mat.name if mat else obj.name}: {n}" for n in shader.left_out]
    # Named by its content too: an edited material is another file, which a running viewport
    # session takes by an update of the volume's `shader` key (viewport.py).
    digest = hashlib.sha1(toml_text.dumps(shader.document).encode()).hexdigest()[:10]
    file_name = f"shader_{_safe_name(obj.name)}_{digest}.toml"
    ex.shaders[file_name] = shader.document
    table = {"file": os.path.abspath(path), "name": _safe_name(obj.name),
             "shader": os.path.join(ex.folder, file_name),
             "density_scale": shader.density_scale * density_factor,
             "bind": {slot: renames.get(a, a) for slot, a in shader.bind.items()},
             "transform": file_transform}
    ex.materials.append((mat, shader, table))
    return table


def _domain(obj, frame, ex):
    """A Mantaflow gas domain: its OpenVDB data cache's file of the frame, placed in the
    domain as Blender places the simulation (mantaflow.py); density per metre of the world,
    as Cycles takes a domain's."""
    path = mantaflow.cache_file(obj, frame, ex.left_out)
    if path is None:
        return None
    require_file(obj, path, frame)
    return volume_table(obj, path, mantaflow.GRIDS, mantaflow.ATTRIBUTE_GRIDS,
                        transform(mantaflow.file_matrix(obj)), 1.0, ex)


def _grouped(table, lightgroup):
    """A light in the Light Group Blender gives its object or world (Object › Shading › Light
    Group): Mirage's `group`, whose lightgroup_<name> pass passes.py delivers."""
    if lightgroup:
        table["group"] = lightgroup
    return table


def _refraction(ex):
    """The scene's one [refraction]: the first volume whose material asks for an index from
    its temperature (physics.py); any other that asks is named."""
    for index, (mat, shader, volume_table) in enumerate(ex.materials):
        table = physics.refraction(mat, shader, volume_table, index, ex.left_out)
        if table is None:
            continue
        if "refraction" in ex.scene:
            ex.left_out.append(f"material '{mat.name}': Index from Temperature (one volume "
                               "bends light in Mirage: the first)")
        else:
            ex.scene["refraction"] = table


def _blurred(obj, table, frame_rate, ex):
    """A volume's velocity keys where the shutter is open (motion.py): a Volume object's
    Velocity Grid, a Mantaflow domain's cached velocity."""
    if obj.type == "VOLUME":
        grids = {g.name for g in obj.data.grids} if obj.data.grids.is_loaded else set()
        table.update(motion.volume_velocity(obj, grids, frame_rate, ex.left_out))
    else:
        table.update(motion.domain_velocity(mantaflow.gas_domain(obj)))


def _objects(depsgraph, final):
    """The evaluated objects that render: instances included, each once. A `final` render's
    (F12's) leaves out what Disable in Renders hides, as its own depsgraph already does,
    whichever depsgraph the export is given (a script's is the viewport's)."""
    for inst in depsgraph.object_instances:
        obj = inst.instance_object if inst.is_instance else inst.object
        if not (final and obj.hide_render):
            yield obj


def export(depsgraph, settings, folder, scene_camera=True):
    """The Export of the depsgraph's scene at its current frame, its files to go in `folder`.
    Without `scene_camera` it has no [film] and [camera]: the viewport gives its own."""
    scene = depsgraph.scene
    ex = Export(folder)
    doc = ex.scene
    if scene_camera:
        doc["film"] = film(scene, settings)
        doc["camera"] = camera(scene, ex)
    doc["render"] = {"integrator": settings.integrator}
    volumes, lights, skipped = [], [], []
    shapes = surfaces.Surfaces()
    shutter = motion.shutter(scene, ex.left_out) if scene_camera else None
    for obj in _objects(depsgraph, scene_camera):
        domain = obj.type == "MESH" and mantaflow.gas_domain(obj) is not None
        if obj.type == "VOLUME" or domain:
            v = (_domain if domain else volume)(obj, scene.frame_current, ex)
            if v is not None:
                if shutter is not None:
                    _blurred(obj, v, motion.fps(scene), ex)
                volumes.append(v)
        elif surfaces.is_geometry(obj):
            shapes.add(obj, folder, _safe_name, ex)
        elif obj.type == "LIGHT":
            lt = light(obj, ex)
            if lt is not None:
                lights.append(_grouped(lt, obj.lightgroup))
        elif obj.type not in ("CAMERA", "EMPTY"):
            skipped.append(obj.name)
    if skipped:
        ex.left_out.append("objects (Mirage renders volumes, meshes and lights): " +
                           ", ".join(skipped))
    dome = world(scene, ex)
    if dome is not None:
        lights.append(_grouped(dome, scene.world.lightgroup))
    if volumes:
        if settings.grid_precision != "float":  # the Grid Precision setting, on every volume
            for v in volumes:
                v["precision"] = settings.grid_precision
        doc["volume"] = volumes
    _refraction(ex)
    shapes.into(doc)
    if lights:
        doc["light"] = lights
    doc["output"] = {"path": os.path.join(folder, "render.exr"), "half": False}
    if shutter is not None:
        doc["camera"]["shutter"] = shutter
        doc["output"]["fps"] = motion.fps(scene)
    return ex
