"""Blender's motion blur as Mirage's (docs/scene-file.md, "Motion blur"; docs/blender.md).

The shutter. Render › Motion Blur opens for `motion_blur_shutter` frames, starting at the
frame (Start), centred on it (Center) or ending at it (End) — the Position, a property of the
Cycles add-on in Blender 3.4 (`scene.cycles.motion_blur_position`; Center without it); Mirage's `[camera] shutter` is
[open, close] in frames relative to the frame, so [0, s], [-s/2, s/2] or [-s, 0]. Mirage takes
each end within ±1 frame: a longer shutter is clamped, with a note. `[output] fps` is the
scene's frame rate (fps / fps_base), with which Mirage turns frames into seconds.

Velocities. A Volume's Velocity Grid names the vector grid (`velocity_grid`) that moves it,
multiplied by Velocity Scale, in object units per frame (Velocity Unit: Frame) or per second
(Second). Mirage reads a volume's velocity in its file's space too, per second, and moves the
volume in that space, so the volume's transform (with the Z-up to Y-up rotation) turns and
scales the motion as Blender's object matrix does: only the unit converts, a per-frame velocity
times the frame rate. A volume without a Velocity Grid does not blur (`velocity = ""`).

A Mantaflow gas domain's data cache holds `velocity`, a staggered (face-centred) vector grid
in world units per second (Cycles' fluid loader reads it so: "relative to seconds"), in the
cache's axes, which mantaflow.py's file matrix turns into the domain's; its Velocity Scale
(Physics › Fluid › Domain) multiplies it, as in Cycles. Measured on the animation test's
smoke (flow velocity 2 m/s up, buoyant): |v| 0.15 to 3.1 m/s.
"""

# Mirage's shutter ends are within this many frames of the frame (docs/scene-file.md).
_LONGEST = 1.0


def fps(scene):
    return scene.render.fps / scene.render.fps_base


def shutter(scene, left_out):
    """Mirage's [open, close] for the scene's Motion Blur, or None when it is off."""
    r = scene.render
    if not r.use_motion_blur:
        return None
    s = float(r.motion_blur_shutter)
    ends = {"START": (0.0, s), "CENTER": (-0.5 * s, 0.5 * s), "END": (-s, 0.0)}
    cycles = getattr(scene, "cycles", None)
    open_, close = ends[getattr(cycles, "motion_blur_position", "CENTER")]
    clamped = [min(max(open_, -_LONGEST), _LONGEST), min(max(close, -_LONGEST), _LONGEST)]
    if clamped != [open_, close]:
        left_out.append(f"motion blur shutter {s:g} frames (Mirage's ends are within ±1 "
                        "frame: clamped)")
    return clamped


def volume_velocity(obj, grids, frame_rate, left_out):
    """The `velocity` and `velocity_scale` keys of a Volume object's [[volume]]."""
    vol = obj.data
    name = vol.velocity_grid
    if not name or (grids and name not in grids):
        if vol.velocity_x_grid or (name and grids):
            left_out.append(f"volume '{obj.name}': velocity grid '{name or vol.velocity_x_grid}' "
                            "(Mirage reads one vector grid the file holds)")
        return {"velocity": ""}
    per_second = vol.velocity_scale * (frame_rate if vol.velocity_unit == "FRAME" else 1.0)
    return {"velocity": name, "velocity_scale": float(per_second)}


def domain_velocity(settings):
    """The `velocity` and `velocity_scale` of a Mantaflow gas domain's [[volume]]."""
    return {"velocity": "velocity", "velocity_scale": float(settings.velocity_scale)}
