"""Builds the add-on tests' .blend (run inside Blender): a VDB smoke stood up from its Y-up
file into Blender's Z-up world and turned, a Principled Volume, a camera, a sun and a dim
constant world, at a small size. Usage:
    blender -b --factory-startup --python-exit-code 1 --python make_scene.py -- \
        CACHE.vdb OUT.blend [--node-extra] [--missing-cache] [--surfaces]
--node-extra puts a Math node on the density (a node Mirage cannot translate); --missing-cache
points the volume at a file that does not exist; --surfaces adds meshes under Principled
BSDFs (stage.py's floor, a mirror, a glass ball) and a holdout cube."""
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

vol = bpy.data.volumes.new("Smoke")
vol.filepath = cache if "--missing-cache" not in argv else cache + ".missing.vdb"
obj = bpy.data.objects.new("Smoke", vol)
scene.collection.objects.link(obj)
# make-asset's fog sphere: a ball of radius 1 m about (0, 1, 0) in its Y-up file. Squashed
# into an ellipsoid longest along the file's up, +90 degrees about X stands that up along +Z;
# then a turn about Z and a move: its silhouette shows every part of the transform.
obj.scale = (0.7, 0.9, 0.35)
obj.rotation_euler = (math.radians(90.0), 0.0, math.radians(30.0))
obj.location = (0.3, -0.2, 0.1)

mat = bpy.data.materials.new("SmokeMaterial")
mat.use_nodes = True
nt = mat.node_tree
nt.nodes.clear()
out_node = nt.nodes.new("ShaderNodeOutputMaterial")
pv = nt.nodes.new("ShaderNodeVolumePrincipled")
pv.inputs["Density"].default_value = 8.0
pv.inputs["Density Attribute"].default_value = "density"
pv.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
pv.inputs["Absorption Color"].default_value = (0.0, 0.0, 0.0, 1.0)
pv.inputs["Anisotropy"].default_value = 0.3
nt.links.new(pv.outputs["Volume"], out_node.inputs["Volume"])
if "--node-extra" in argv:
    math_node = nt.nodes.new("ShaderNodeMath")
    math_node.name = "Density Boost"
    math_node.operation = "MULTIPLY"
    math_node.inputs[0].default_value = 3.0
    math_node.inputs[1].default_value = 2.0
    nt.links.new(math_node.outputs[0], pv.inputs["Density"])
vol.materials.append(mat)

# Aimed at the plume's middle.
stage.camera(scene, Vector((1.7, -2.9, 1.6)), Vector((0.3, -0.2, 1.0)), 40.0)
stage.sun_and_world(scene)
stage.small_output(scene)
if "--surfaces" in argv:
    stage.surfaces(scene)
scene.frame_set(1)
bpy.ops.wm.save_as_mainfile(filepath=out)
print("MAKE_SCENE wrote", out)
