"""Mirage's panels in the Render Properties, shown when Mirage is the render engine."""
import bpy


class MIRAGE_PT_render(bpy.types.Panel):
    bl_label = "Mirage"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"MIRAGE"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        s = context.scene.mirage
        layout = self.layout
        layout.use_property_split = True
        layout.prop(s, "integrator")
        layout.prop(s, "samples")
        layout.prop(s, "preview_samples")
        layout.prop(s, "seed")
        col = layout.column(heading="Stop")
        col.prop(s, "time_limit")
        col.prop(s, "noise_threshold")
        layout.prop(s, "quality")
        layout.prop(s, "threads")


def _compatible_panels():
    """Blender's own panels that apply to any engine (dimensions, output, colour management)."""
    keep = ("RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_output",
            "RENDER_PT_color_management", "RENDER_PT_film", "DATA_PT_lens", "DATA_PT_camera",
            "DATA_PT_light", "DATA_PT_volume_file", "DATA_PT_volume_grids",
            "MATERIAL_PT_preview", "EEVEE_MATERIAL_PT_volume", "WORLD_PT_context_world")
    return [getattr(bpy.types, n) for n in keep if hasattr(bpy.types, n)]


def register():
    bpy.utils.register_class(MIRAGE_PT_render)
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.add("MIRAGE")


def unregister():
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.discard("MIRAGE")
    bpy.utils.unregister_class(MIRAGE_PT_render)
