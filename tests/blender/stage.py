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
