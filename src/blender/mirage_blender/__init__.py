"""Mirage, the spectral volume renderer, as a Blender render engine (docs/blender.md).

Installed by pipeline/install-blender-addon.sh; the Python module it renders with is the one
built in <build>/python (module_path.py finds it)."""
bl_info = {
    "name": "Mirage",
    "description": "Mirage spectral volume renderer: OpenVDB smoke, fire and clouds",
    "author": "Mirage",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Render Properties › Render Engine › Mirage",
    "category": "Render",
}

if "bpy" in locals():
    import importlib
    for _m in (units, toml_text, shading, physics, mantaflow, export, viewport,  # noqa
               passes, module_path, properties, engine, ui):
        importlib.reload(_m)

import bpy

from . import (engine, export, mantaflow, module_path, passes, physics,  # noqa
               properties, shading, toml_text, ui, units, viewport)


class MiragePreferences(bpy.types.AddonPreferences):
    bl_idname = __package__

    python_dir: bpy.props.StringProperty(
        name="Mirage Python module", subtype="DIR_PATH",
        default=module_path.recorded_dir(),
        description="The folder holding the built module's package, <build>/python")

    def draw(self, context):
        self.layout.prop(self, "python_dir")


_CLASSES = (MiragePreferences, properties.MirageRenderSettings, passes.MirageViewLayerSettings,
            physics.MirageMaterialSettings, engine.MirageRenderEngine)


def register():
    for cls in _CLASSES:
        bpy.utils.register_class(cls)
    bpy.types.Scene.mirage = bpy.props.PointerProperty(type=properties.MirageRenderSettings)
    bpy.types.ViewLayer.mirage = bpy.props.PointerProperty(type=passes.MirageViewLayerSettings)
    bpy.types.Material.mirage = bpy.props.PointerProperty(type=physics.MirageMaterialSettings)
    ui.register()


def unregister():
    ui.unregister()
    del bpy.types.Material.mirage
    del bpy.types.ViewLayer.mirage
    del bpy.types.Scene.mirage
    for cls in reversed(_CLASSES):
        bpy.utils.unregister_class(cls)
