"""The view layer's passes as Blender render passes from Mirage's AOVs (docs/aovs.md): which
passes a view layer asks for, the Mirage pass that fills each, and its pixels in the render
result. Blender's own switches where Blender has one (View Layer › Passes: Z, Emission; Light
Groups), the add-on's for the passes only Mirage has (view_layer.mirage)."""
from dataclasses import dataclass

import bpy
import numpy as np


@dataclass(frozen=True)
class Pass:
    name: str       # the render pass, as Blender's compositor and multilayer EXR name it
    chan_id: str    # its channels' letters
    kind: str       # "COLOR" or "VALUE"
    aov: str        # the Mirage pass that fills it
    switch: str     # the view layer's property that asks for it ("mirage." the add-on's)


# Cycles' names where Cycles has the pass, so compositing set-ups carry over. The light-path
# passes (Emit, VolumeDir, VolumeInd) sum to Combined's colour.
PASSES = (
    Pass("Depth", "Z", "VALUE", "depth", "use_pass_z"),
    Pass("Emit", "RGB", "COLOR", "emission", "use_pass_emit"),
    Pass("VolumeDir", "RGB", "COLOR", "volume_direct", "mirage.use_pass_volume_direct"),
    Pass("VolumeInd", "RGB", "COLOR", "volume_indirect", "mirage.use_pass_volume_indirect"),
    Pass("Albedo", "RGB", "COLOR", "albedo", "mirage.use_pass_albedo"),
    Pass("Transmittance", "RGB", "COLOR", "transmittance", "mirage.use_pass_transmittance"),
)


class MirageViewLayerSettings(bpy.types.PropertyGroup):
    use_pass_volume_direct: bpy.props.BoolProperty(
        name="Volume Direct", description="Light scattered once in a medium (volume_direct)")
    use_pass_volume_indirect: bpy.props.BoolProperty(
        name="Volume Indirect",
        description="Light scattered more than once, first in a medium (volume_indirect)")
    use_pass_albedo: bpy.props.BoolProperty(
        name="Albedo", description="Opacity-weighted single-scattering albedo, for denoisers")
    use_pass_transmittance: bpy.props.BoolProperty(
        name="Transmittance", description="Transmittance of the camera ray per channel")


def _switched_on(view_layer, switch):
    owner = view_layer
    *path, prop = switch.split(".")
    for p in path:
        owner = getattr(owner, p)
    return bool(getattr(owner, prop))


def enabled(view_layer):
    """The passes the view layer asks for, in PASSES' order, then its Light Groups: Cycles'
    Combined_<name>, Mirage's lightgroup_<name> (the beauty lit by that group's lights)."""
    chosen = [p for p in PASSES if _switched_on(view_layer, p.switch)]
    return chosen + [Pass(f"Combined_{g.name}", "RGB", "COLOR", f"lightgroup_{g.name}", "")
                     for g in view_layer.lightgroups]


def lit(chosen, groups):
    """The passes Mirage can give: a light group no light belongs to is an error in Mirage,
    and an empty pass in Blender (write() leaves it black)."""
    return [p for p in chosen if not p.aov.startswith("lightgroup_") or
            p.aov[len("lightgroup_"):] in groups]


def register_passes(engine, scene, view_layer):
    """RenderEngine.update_render_passes: the compositor's sockets and the EXR's layers."""
    engine.register_pass(scene, view_layer, "Combined", 4, "RGBA", "COLOR")
    for p in enabled(view_layer):
        engine.register_pass(scene, view_layer, p.name, len(p.chan_id), p.chan_id, p.kind)


def write(layer, image, chosen):
    """Each chosen pass's pixels into the render layer, rows bottom to top as Blender's."""
    for p in chosen:
        pixels = np.flipud(image.aovs[p.aov]).astype(np.float32)
        # Mirage's depth is +inf where the ray never gets half opaque; Blender's Z pass has
        # 1e10 for the background (Cycles' and Eevee's), which the compositor's nodes expect.
        pixels[~np.isfinite(pixels)] = 1.0e10
        layer.passes[p.name].rect = np.ascontiguousarray(pixels).reshape(-1, len(p.chan_id))
