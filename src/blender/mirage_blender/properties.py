"""Mirage's render settings on a Blender scene (scene.mirage), what `mirage render`'s options
set (docs/cli.md): the integrator, samples and seed, and what stops a render in passes."""
import bpy

INTEGRATORS = [
    ("auto", "Auto", "Mirage picks per scene (docs/cli.md, \"The default integrator\")"),
    ("single", "Single scattering", "Direct light in the media, no multiple scattering"),
    ("volpath", "Path tracer", "The reference volumetric path tracer"),
    ("photon", "Photon mapping", "Volumetric photon mapping, progressive"),
]
PRECISIONS = [
    ("float", "Float", "32-bit floats: the grids as stored (docs/scene-file.md, \"Grid precision\")"),
    ("half", "Half", "16 bits per voxel: error at most 1/131070 of a grid's maximum"),
    ("fp8", "8-bit", "8 bits per voxel: error at most 1/510 of a grid's maximum"),
    ("fp4", "4-bit", "4 bits per voxel: error at most 1/30 of a grid's maximum"),
    ("fpn", "Adaptive", "1 to 16 bits per leaf, error at most 1/1000 of a grid's maximum"),
]
QUALITIES = [
    ("NONE", "None", "No preset: the samples and settings as given"),
    ("draft", "Draft", "--quality draft"),
    ("preview", "Preview", "--quality preview"),
    ("final", "Final", "--quality final"),
]


class MirageRenderSettings(bpy.types.PropertyGroup):
    integrator: bpy.props.EnumProperty(name="Integrator", items=INTEGRATORS, default="auto")
    samples: bpy.props.IntProperty(name="Samples", default=16, min=1, soft_max=4096,
                                   description="Samples per pixel (film.spp)")
    preview_samples: bpy.props.IntProperty(
        name="Viewport Samples", default=16, min=1, soft_max=4096,
        description="Samples per pixel of the viewport's Rendered shading, one per pass")
    seed: bpy.props.IntProperty(name="Seed", default=0, min=0, description="film.seed")
    time_limit: bpy.props.FloatProperty(
        name="Time Limit", default=0.0, min=0.0, unit="TIME_ABSOLUTE",
        description="Seconds: render in passes until then (0: no limit)")
    noise_threshold: bpy.props.FloatProperty(
        name="Noise Threshold", default=0.0, min=0.0, precision=4,
        description="Stop when the estimated relative error falls below it (0: off)")
    quality: bpy.props.EnumProperty(name="Quality", items=QUALITIES, default="NONE")
    grid_precision: bpy.props.EnumProperty(
        name="Grid Precision", items=PRECISIONS, default="float",
        description="How the volumes' grids are held in memory ([[volume]] precision)")
    threads: bpy.props.IntProperty(name="Threads", default=0, min=0,
                                   description="Render threads (0: every core)")

    def render_arguments(self):
        """The keyword arguments of mirage.Session and mirage.render these settings give."""
        args = {"threads": self.threads}
        if self.time_limit > 0.0:
            args["time_limit"] = self.time_limit
        if self.noise_threshold > 0.0:
            args["noise_threshold"] = self.noise_threshold
        if self.quality != "NONE":
            args["quality"] = self.quality
        return args
