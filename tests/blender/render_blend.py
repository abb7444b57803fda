"""Renders a .blend inside Blender for the add-on tests, with the add-on loaded from the
repository (src/blender), not from the user's configuration. Usage:
    blender -b --factory-startup --python-exit-code 1 --python render_blend.py -- \
        FILE.blend OUT.exr mirage|cycles SAMPLES [--export SCENE.toml] [--passes] [--frame N]
        [--physics] [--velocity FILE.vdb] [--blur START|CENTER|END]
mirage: the add-on renders (SAMPLES per pixel, the path tracer, seed 0); --export also writes
the scene it renders as TOML (with its shader files beside it); --passes turns on every render
pass Mirage fills, three light groups (the sun's, the world's, one empty), and writes a
multilayer EXR; --physics turns on every Mirage-only physics of
the material SmokeMaterial (make_scene.py's), a blackbody on its density for the heat haze, and
stands the smoke up unturned and unsquashed (Mirage's heat haze needs that). --frame N renders
frame N. --velocity points the volume Smoke at FILE.vdb and its Velocity Grid at the file's
`vel` (per frame, scale 0.5), its density 40; --blur turns Render › Motion Blur on, a shutter of 0.5 frames at
that position. cycles: Cycles on the CPU, SAMPLES per pixel, 64 volume bounces, no denoising, no clamping, a 1-pixel box filter.
Prints `REPORT <type> <message>` for each report of the render, `RESULT <status>` after it, and
`SECONDS <s>` (the render alone)."""
import math
import os
import sys
import time

import bpy

argv = sys.argv[sys.argv.index("--") + 1:]
blend, out, engine, samples = argv[0], argv[1], argv[2], int(argv[3])
export_path = argv[argv.index("--export") + 1] if "--export" in argv else None
integrator = argv[argv.index("--integrator") + 1] if "--integrator" in argv else "volpath"

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_from_source  # noqa: E402

bpy.ops.wm.open_mainfile(filepath=blend)
mirage_blender = addon_from_source.load()
scene = bpy.context.scene
if "--frame" in argv:
    scene.frame_set(int(argv[argv.index("--frame") + 1]))
scene.render.filepath = out
scene.render.use_file_extension = False

if engine == "mirage":
    scene.render.engine = "MIRAGE"
    scene.mirage.samples = samples
    scene.mirage.integrator = integrator
    scene.mirage.seed = 0
    if "--passes" in argv:
        view_layer = bpy.context.view_layer
        view_layer.use_pass_z = view_layer.use_pass_emit = True
        for name in ("volume_direct", "volume_indirect", "albedo", "transmittance"):
            setattr(view_layer.mirage, "use_pass_" + name, True)
        # Light groups: the sun in "key", the world in "sky", and "rim" with no light.
        for group in ("key", "sky", "rim"):
            view_layer.lightgroups.add(name=group)
        bpy.data.objects["Sun"].lightgroup = "key"
        scene.world.lightgroup = "sky"
        scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    if "--physics" in argv:
        mat = bpy.data.materials["SmokeMaterial"]
        pv = next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeVolumePrincipled")
        pv.inputs["Blackbody Intensity"].default_value = 1.0
        pv.inputs["Temperature"].default_value = 1500.0
        pv.inputs["Temperature Attribute"].default_value = "density"
        m = mat.mirage
        m.use_chlorophyll, m.chlorophyll, m.chlorophyll_fluorescence = True, 4.0, 0.02
        m.use_cdom, m.cdom_covaries = True, True
        m.fluorescence, m.fluorescence_peak = 0.3, 520.0
        m.use_index_from_temperature = True
        # Mirage's heat haze needs the grid unrotated in its axes, at one scale: the file's
        # Y-up stood up, no turn, no squash.
        smoke = bpy.data.objects["Smoke"]
        smoke.rotation_euler, smoke.scale = (math.radians(90.0), 0.0, 0.0), (0.8, 0.8, 0.8)
    if "--velocity" in argv:
        vol = bpy.data.objects["Smoke"].data
        vol.filepath = argv[argv.index("--velocity") + 1]
        vol.grids.load()
        vol.velocity_grid, vol.velocity_unit, vol.velocity_scale = "vel", "FRAME", 0.5
        # make-asset's smoke is thinner than the fog sphere: denser, it is opaque in places.
        pv = bpy.data.materials["SmokeMaterial"].node_tree.nodes["Principled Volume"]
        pv.inputs["Density"].default_value = 40.0
    if "--blur" in argv:
        scene.render.use_motion_blur, scene.render.motion_blur_shutter = True, 0.5
        scene.cycles.motion_blur_position = argv[argv.index("--blur") + 1]
    if export_path:
        folder = os.path.dirname(os.path.abspath(export_path))
        ex = mirage_blender.export.export(bpy.context.evaluated_depsgraph_get(), scene.mirage,
                                          folder)
        ex.write_scene(export_path)
else:
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device, c.samples, c.use_adaptive_sampling, c.use_denoising = "CPU", samples, False, False
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    bounces = 0 if integrator == "single" else 64
    c.volume_bounces, c.max_bounces, c.transparent_max_bounces = bounces, bounces, 1024
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    c.seed = 0

if os.path.exists(out):
    os.remove(out)
t0 = time.perf_counter()
try:
    status = bpy.ops.render.render(write_still=True)
except RuntimeError as e:
    status = {"RAISED: " + str(e).replace("\n", " ")}
seconds = time.perf_counter() - t0
for kind, message in mirage_blender.engine.REPORTS:
    print("REPORT", kind, message.replace("\n", " "), flush=True)
print("RESULT", ",".join(sorted(status)), "written" if os.path.isfile(out) else "no-file",
      flush=True)
print(f"SECONDS {seconds:.4f}", flush=True)
