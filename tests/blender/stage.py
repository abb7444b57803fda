"""What the tests' scenes share (make_scene.py, make_smoke.py): a camera aimed at a point, the
coloured sun and dim blue-grey world the renderers are compared under, and a small 32-bit EXR
output with Film › Transparent."""
import math

import bpy


def camera(scene, location, aim, lens):
    """The scene's camera at `location` looking at `aim` (its local -Z, +Y up)."""
    cam = bpy.data.cameras.new("Camera")
    cam.lens = lens
    cam.clip_end = 1000.0
    cam_obj = bpy.data.objects.new("Camera", cam)
    cam_obj.location = location
    cam_obj.rotation_euler = (aim - cam_obj.location).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj


def sun_and_world(scene):
    sun = bpy.data.lights.new("Sun", type="SUN")
    sun.energy = 3.0
    sun.angle = 0.0
    sun.color = (1.0, 0.95, 0.9)
    sun_obj = bpy.data.objects.new("Sun", sun)
    sun_obj.rotation_euler = (math.radians(40.0), math.radians(10.0), math.radians(-60.0))
    scene.collection.objects.link(sun_obj)
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.2, 0.25, 0.35, 1.0)
    bg.inputs["Strength"].default_value = 0.5
    scene.world = world


def small_output(scene):
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = 48, 64, 100
    r.film_transparent = True
    r.use_compositing = r.use_sequencer = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_depth = "32"
    r.image_settings.color_mode = "RGBA"
    scene.view_settings.view_transform = "Standard"


def _principled(name, **inputs):
    """A material of one Principled BSDF with `inputs` (socket name with _ for spaces)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes["Principled BSDF"]
    for socket, value in inputs.items():
        node.inputs[socket.replace("_", " ")].default_value = value
    return mat


def _mesh(scene, name, make, location, mat):
    make(location=location)
    obj = bpy.context.active_object
    obj.name = name
    if mat is not None:
        obj.data.materials.append(mat)
    return obj


def surfaces(scene):
    """A floor under the smoke (diffuse), a mirror cube and a smooth glass ball beside it, and
    a holdout cube (Visibility › Holdout): each of the add-on's surface translations."""
    floor = _mesh(scene, "Floor", bpy.ops.mesh.primitive_plane_add, (0.0, 0.0, 0.0),
                  _principled("FloorMaterial", Base_Color=(0.6, 0.5, 0.4, 1.0)))
    floor.scale = (4.0, 4.0, 1.0)
    mirror = _mesh(scene, "Mirror", bpy.ops.mesh.primitive_cube_add, (-0.9, 0.4, 0.4),
                   _principled("MirrorMaterial", Metallic=1.0, Roughness=0.0))
    mirror.scale = (0.3, 0.3, 0.4)
    mirror.rotation_euler = (0.0, 0.0, math.radians(25.0))
    ball = _mesh(scene, "Glass", bpy.ops.mesh.primitive_uv_sphere_add, (1.0, 0.3, 0.3),
                 _principled("GlassMaterial", Transmission=1.0, Roughness=0.0, IOR=1.45))
    ball.scale = (0.3, 0.3, 0.3)
    bpy.ops.object.shade_smooth()
    holdout = _mesh(scene, "Holdout", bpy.ops.mesh.primitive_cube_add, (0.6, -1.0, 0.15), None)
    holdout.scale = (0.15, 0.15, 0.15)
    holdout.is_holdout = True
