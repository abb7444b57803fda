"""Mirage's panels: its render settings (Render Properties), its passes (View Layer), a
material's Mirage-only physics (Material) and a volume's velocity for motion blur (Volume
data: Blender draws those settings for Cycles only), shown when Mirage is the render engine."""
import bpy


class _MiragePanel:
    """A Properties editor panel shown when Mirage is the render engine."""
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    COMPAT_ENGINES = {"MIRAGE"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def split_layout(self):
        """The panel's layout with each label left of its field, as Blender's own panels."""
        layout = self.layout
        layout.use_property_split = True
        return layout


class _DataPanel(_MiragePanel):
    """A panel of one kind of data block (`context_member`: material, volume, …), shown when
    the context holds one."""
    context_member = ""

    @classmethod
    def poll(cls, context):
        return super().poll(context) and getattr(context, cls.context_member, None) is not None


class MIRAGE_PT_render(_MiragePanel, bpy.types.Panel):
    bl_label = "Mirage"
    bl_context = "render"

    def draw(self, context):
        s = context.scene.mirage
        layout = self.split_layout()
        layout.prop(s, "integrator")
        layout.prop(s, "samples")
        layout.prop(s, "preview_samples")
        layout.prop(s, "grid_precision")
        layout.prop(s, "seed")
        col = layout.column(heading="Stop")
        col.prop(s, "time_limit")
        col.prop(s, "noise_threshold")
        layout.prop(s, "quality")
        layout.prop(s, "threads")


class MIRAGE_PT_passes(_MiragePanel, bpy.types.Panel):
    """View Layer properties: the render passes Mirage fills from its AOVs (passes.py)."""
    bl_label = "Mirage Passes"
    bl_context = "view_layer"

    def draw(self, context):
        view_layer = context.view_layer
        layout = self.split_layout()
        col = layout.column(heading="Data")
        col.prop(view_layer, "use_pass_combined")
        col.prop(view_layer, "use_pass_z")
        col.prop(view_layer.mirage, "use_pass_albedo")
        col.prop(view_layer.mirage, "use_pass_transmittance")
        col = layout.column(heading="Light")
        col.prop(view_layer, "use_pass_emit", text="Emission")
        col.prop(view_layer.mirage, "use_pass_volume_direct")
        col.prop(view_layer.mirage, "use_pass_volume_indirect")


class MIRAGE_PT_material_physics(_DataPanel, bpy.types.Panel):
    """Material properties: the Mirage-only physics beside the Principled Volume (physics.py)."""
    bl_label = "Mirage Physics"
    bl_context = "material"
    context_member = "material"

    def draw(self, context):
        s = context.material.mirage
        layout = self.split_layout()
        col = layout.column(heading="Sea Water")
        col.prop(s, "use_chlorophyll")
        sub = col.column()
        sub.active = s.use_chlorophyll
        sub.prop(s, "chlorophyll")
        sub.prop(s, "chlorophyll_fluorescence")
        col.prop(s, "use_cdom")
        sub = col.column()
        sub.active = s.use_cdom
        sub.prop(s, "cdom_covaries")
        sub.prop(s, "cdom_absorption")
        sub.prop(s, "cdom_slope")
        col = layout.column(heading="Medium")
        col.prop(s, "fluorescence")
        sub = col.column()
        sub.active = s.fluorescence > 0.0
        sub.prop(s, "fluorescence_peak")
        sub.prop(s, "fluorescence_width")
        col = layout.column(heading="Curved Light")
        col.prop(s, "use_index_from_temperature")
        sub = col.column()
        sub.active = s.use_index_from_temperature
        sub.prop(s, "ambient_temperature")


class MIRAGE_PT_volume_motion(_DataPanel, bpy.types.Panel):
    """Volume data: the velocity grid Mirage's motion blur reads (motion.py)."""
    bl_label = "Motion Blur"
    bl_context = "data"
    context_member = "volume"

    def draw(self, context):
        layout = self.split_layout()
        for name in ("velocity_grid", "velocity_unit", "velocity_scale"):
            layout.prop(context.volume, name)


_PANELS = (MIRAGE_PT_render, MIRAGE_PT_passes, MIRAGE_PT_material_physics,
           MIRAGE_PT_volume_motion)


def _compatible_panels():
    """Blender's own panels that apply to any engine (dimensions, output, colour management),
    and Cycles' Motion Blur panel, whose shutter and position Mirage reads (motion.py)."""
    keep = ("RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_output",
            "RENDER_PT_color_management", "RENDER_PT_film", "DATA_PT_lens", "DATA_PT_camera",
            "DATA_PT_light", "DATA_PT_volume_file", "DATA_PT_volume_grids",
            "MATERIAL_PT_preview", "EEVEE_MATERIAL_PT_volume", "WORLD_PT_context_world",
            "CYCLES_RENDER_PT_motion_blur")
    return [getattr(bpy.types, n) for n in keep if hasattr(bpy.types, n)]


def register():
    for panel in _PANELS:
        bpy.utils.register_class(panel)
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.add("MIRAGE")


def unregister():
    for panel in _compatible_panels():
        panel.COMPAT_ENGINES.discard("MIRAGE")
    for panel in reversed(_PANELS):
        bpy.utils.unregister_class(panel)
