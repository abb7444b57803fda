"""Builds the animation test's .blend (run inside Blender): a Mantaflow smoke domain over a
small cube emitter, 16 cells across, its OpenVDB data cache baked for frames 1 to 6 into
CACHE_DIR, a camera, a sun and a dim world. Usage:
    blender -b --factory-startup --python-exit-code 1 --python make_smoke.py -- CACHE_DIR OUT.blend
"""
import math
import os
import sys

import bpy
from mathutils import Vector

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stage  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:]
cache, out = argv[0], argv[1]

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.mesh.primitive_cube_add(size=0.6, location=(0.0, 0.0, 0.4))
emitter = bpy.context.active_object
emitter.select_set(True)
bpy.ops.object.quick_smoke()
emitter.hide_render = True           # not part of the shot: neither renderer shows it
domain = next(o for o in scene.objects if o.name.startswith("Smoke Domain"))
domain.rotation_euler = (0.0, 0.0, math.radians(20.0))  # the cache's placement turns with it
settings = domain.modifiers["Fluid"].domain_settings
settings.resolution_max = 16
settings.cache_directory = cache
settings.cache_data_format = "OPENVDB"
settings.cache_type = "MODULAR"
settings.cache_frame_start, settings.cache_frame_end = 1, 6
# Smoke that shoots up: the frames differ plainly (frame 3 a puff, frame 6 a column).
settings.time_scale = 2.0
flow = emitter.modifiers["Fluid"].flow_settings
flow.use_initial_velocity = True
flow.velocity_coord = (0.0, 0.0, 2.0)
with bpy.context.temp_override(object=domain, active_object=domain):
    assert bpy.ops.fluid.bake_data() == {"FINISHED"}

stage.camera(scene, Vector((3.0, -4.5, 2.5)), Vector((0.0, 0.0, 1.0)), 35.0)
stage.sun_and_world(scene)
stage.small_output(scene)
scene.frame_start, scene.frame_end, scene.frame_step = 3, 6, 3  # `-a`: frames 3 and 6
scene.frame_set(1)
bpy.ops.wm.save_as_mainfile(filepath=out)
print("MAKE_SMOKE wrote", out)
