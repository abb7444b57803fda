"""Mantaflow gas domains (Blender's smoke and fire): the OpenVDB data cache a bake writes,
`<cache directory>/data/fluid_data_<frame, 4 digits>.vdb`, as a Mirage volume.

Where the grids are. Mantaflow simulates on a grid of cells of one size dx in the world,
dx = the domain's longest world dimension / Resolution Divisions, starting at the corner of the
domain's bounding box; the cache's grids keep that in their transform: voxel size dx, no
rotation, no offset, so cell i (covering i·dx to (i+1)·dx from the corner, in the domain's
scaled but unrotated axes) is OpenVDB's voxel i, centred at i·dx. A point c of the file is
then, in the domain's world, R·(c + o) + t, with R, t the domain's rotation and location and
o = S·b + dx/2 (b the bounding box's lower corner in object space, S the object's scale)."""
import os

import bpy
from mathutils import Matrix, Vector

# The grids a gas domain's data cache holds, and the attribute names Blender's materials read
# them by (Cycles' fluid attributes): "heat" is the file's "temperature" grid.
GRIDS = {"density", "flame", "temperature", "velocity", "shadow"}
ATTRIBUTE_GRIDS = {"heat": "temperature"}


def gas_domain(obj):
    """The domain settings of a Fluid modifier's gas domain on `obj`, or None."""
    for mod in obj.modifiers:
        if mod.type == "FLUID" and mod.fluid_type == "DOMAIN":
            settings = mod.domain_settings
            return settings if settings.domain_type == "GAS" else None
    return None


def cache_file(obj, frame, left_out):
    """The data cache's file for `frame`; None outside the cache's frame range (no smoke)."""
    settings = gas_domain(obj)
    if settings.cache_data_format != "OPENVDB":
        left_out.append(f"domain '{obj.name}': cache format {settings.cache_data_format} "
                        "(Mirage reads the OpenVDB data cache)")
        return None
    if settings.use_adaptive_domain:
        left_out.append(f"domain '{obj.name}': adaptive domain (placed as the whole domain)")
    if not settings.cache_frame_start <= frame <= settings.cache_frame_end:
        return None
    folder = bpy.path.abspath(settings.cache_directory, library=obj.library)
    return os.path.join(folder, "data", f"fluid_data_{frame:04d}.vdb")


def file_matrix(obj):
    """The cache file's coordinates to Blender's world (the module's docstring)."""
    settings = gas_domain(obj)
    loc, rot, scale = obj.matrix_world.decompose()
    lower = Vector([min(corner[i] for corner in obj.bound_box) for i in range(3)])
    upper = Vector([max(corner[i] for corner in obj.bound_box) for i in range(3)])
    size = (upper - lower) * scale
    dx = max(abs(v) for v in size) / settings.resolution_max
    offset = lower * scale + Vector((dx, dx, dx)) / 2.0
    return Matrix.Translation(loc) @ rot.to_matrix().to_4x4() @ Matrix.Translation(offset)
