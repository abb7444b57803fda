"""The viewport check, run inside Blender with a window (under Xvfb, Mesa's software OpenGL), the
add-on loaded from the repository. Usage:
    blender FILE.blend --factory-startup --python viewport_blend.py -- SHOT.png
It sets the 3D viewport to Rendered shading with Mirage, seen through the scene's camera, waits
for two passes, takes a screenshot of the viewport, then makes the sun three times as strong
and waits for the next image; then edits the material's colour, its Mirage physics, moves the
camera (the view through it), and adds a point light, waiting for the image after each. Prints
`VIEWPORT <key> <value>` lines (blender_check.py checks them), then quits; `VIEWPORT failed
<why>` when a wait runs out."""
import os
import sys
import time

import bpy
import numpy as np

shot_path = sys.argv[sys.argv.index("--") + 1]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import addon_from_source  # noqa: E402

TIMEOUT = 60.0
MARGIN = 4  # pixels of the viewport's edge: Blender's area outline
mirage_blender = addon_from_source.load()
RECORD = mirage_blender.viewport.RECORD


def say(key, value):
    print("VIEWPORT", key, value, flush=True)


def view3d():
    win = bpy.context.window_manager.windows[0]
    area = next(a for a in win.screen.areas if a.type == "VIEW_3D")
    return win, area


def set_up():
    """Mirage's Rendered shading of the camera's view, nothing drawn over it: no overlays,
    header or toolbars, no dither; an opaque film, so the world is the background."""
    scene = bpy.context.scene
    scene.render.engine = "MIRAGE"
    scene.render.film_transparent = False
    scene.render.dither_intensity = 0.0
    scene.render.preview_pixel_size = "1"
    scene.mirage.preview_samples = 8
    scene.mirage.integrator = "single"
    shrink_view3d()
    _, area = view3d()
    space = area.spaces[0]
    for region in ("header", "tool_header", "toolbar", "ui", "hud"):
        setattr(space, f"show_region_{region}", False)
    space.overlay.show_overlays = False
    space.show_gizmo = False
    scene.camera.data.show_passepartout = False
    space.region_3d.view_perspective = "CAMERA"
    space.shading.type = "RENDERED"


def shrink_view3d():
    """A quarter of the 3D viewport (Blender's window is 640 x 480 at least): the viewport split
    across and down, the other parts made outliners, for a small render."""
    win, area = view3d()
    for direction in ("VERTICAL", "HORIZONTAL"):
        with bpy.context.temp_override(window=win, screen=win.screen, area=area):
            bpy.ops.screen.area_split(direction=direction, factor=0.5)
        others = [a for a in win.screen.areas if a.type == "VIEW_3D" and a != area]
        for other in others:
            other.type = "OUTLINER"


def screenshot():
    """The viewport's window region as float RGB, rows bottom to top like the render's."""
    win, area = view3d()
    region = next(r for r in area.regions if r.type == "WINDOW")
    with bpy.context.temp_override(window=win, screen=win.screen, area=area):
        bpy.ops.screen.screenshot_area(filepath=shot_path)
    img = bpy.data.images.load(shot_path)
    w, h = img.size
    pixels = np.array(img.pixels[:], dtype=np.float32).reshape(h, w, img.channels)[..., :3]
    x, y = region.x - area.x, region.y - area.y
    return pixels[y:y + region.height, x:x + region.width]


def srgb(linear):
    """The Standard view transform on an sRGB display: the sRGB encoding (IEC 61966-2-1)."""
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1.0 / 2.4) - 0.055)


def steps():
    """The check as a generator: each yield waits a timer tick; Blender redraws in between."""
    t0 = time.perf_counter()
    set_up()
    while RECORD["images"] == 0 and not RECORD["error"]:
        if time.perf_counter() - t0 > TIMEOUT:
            return say("failed", "no image")
        yield
    say("rendered_to_image_seconds", f"{time.perf_counter() - t0:.3f}")
    while RECORD["passes"] < 2 and not RECORD["error"]:
        if time.perf_counter() - t0 > TIMEOUT:
            return say("failed", "no second pass")
        yield
    images = RECORD["images"]
    while RECORD["images"] == images and RECORD["passes"] < 8:  # drawn: one redraw more
        yield
    say("first_image_seconds", f"{RECORD['first_image_seconds'][0]:.3f}")
    say("error", RECORD["error"] or "none")
    for _ in range(5):
        yield
    shot = screenshot()
    engine_pixels = viewport_pixels()
    say("shape", " ".join("{}x{}".format(*a.shape[:2]) for a in (shot, engine_pixels)))
    if shot.shape[:2] == engine_pixels.shape[:2]:
        # Inside the area's outline; the arrows that bring back the hidden toolbars stay in
        # the corners, a few percent of the pixels.
        inner = (slice(MARGIN, -MARGIN),) * 2
        difference = np.abs(shot[inner] - srgb(engine_pixels[inner][..., :3]))
        say("drawn_error_p95", f"{np.percentile(difference.max(axis=-1), 95):.4f}")
        smoke = engine_pixels[..., 3] > 0.5
        background = engine_pixels[..., 3] < 0.01
        contrast = np.abs(shot[smoke].mean(axis=0) - shot[background].mean(axis=0)).max()
        say("smoke_pixels", int(np.count_nonzero(smoke)))
        say("smoke_contrast", f"{contrast:.4f}")
    restarts = RECORD["restarts"]
    say("restarts_before_edit", restarts)
    say("passes_before_edit", RECORD["passes"])
    images = RECORD["images"]
    edited = time.perf_counter()
    bpy.data.lights["Sun"].energy *= 3.0
    while RECORD["images"] == images or RECORD["restarts"] == restarts:
        if time.perf_counter() - edited > TIMEOUT:
            return say("failed", "no image after the edit")
        yield
    say("edit_to_image_seconds", f"{time.perf_counter() - edited:.3f}")
    say("restarts_after_edit", RECORD["restarts"])
    say("passes_after_edit", RECORD["passes"])
    say("update_kind", RECORD["last_restart"])
    for what, edit in EDITS:
        restarts, images = RECORD["restarts"], RECORD["images"]
        edited = time.perf_counter()
        edit()
        while RECORD["restarts"] == restarts or RECORD["images"] == images:
            if time.perf_counter() - edited > TIMEOUT:
                return say("failed", f"no image after the edit of the {what}")
            yield
        say(f"{what}_edit", f"{RECORD['last_restart']} {time.perf_counter() - edited:.3f}")
    restarts = RECORD["restarts"]
    added = time.perf_counter()
    lamp = bpy.data.lights.new("Added", type="POINT")
    bpy.context.scene.collection.objects.link(bpy.data.objects.new("Added", lamp))
    while RECORD["restarts"] == restarts or RECORD["passes"] == 0:
        if time.perf_counter() - added > TIMEOUT:
            return say("failed", "no image after adding a light")
        yield
    say("added_light_to_image_seconds", f"{time.perf_counter() - added:.3f}")
    say("added_light_kind", RECORD["last_restart"])
    say("done", "ok")


def _edit_material():
    mat = bpy.data.materials["SmokeMaterial"]
    pv = next(n for n in mat.node_tree.nodes if n.bl_idname == "ShaderNodeVolumePrincipled")
    pv.inputs["Color"].default_value = (0.9, 0.5, 0.3, 1.0)


def _edit_physics():
    bpy.data.materials["SmokeMaterial"].mirage.fluorescence = 0.5


def _move_camera():
    bpy.context.scene.camera.location.x += 0.2


# Edits that keep the scene's keys: each an update of the running session.
EDITS = (("material", _edit_material), ("physics", _edit_physics), ("camera", _move_camera))


def viewport_pixels():
    """The image the viewport's engine drew last (its texture's pixels), bottom row first."""
    for render in mirage_blender.viewport.LIVE:
        if render.drawn is not None:
            return render.drawn
    return np.zeros((0, 0, 4), dtype=np.float32)


def tick(generator=steps()):
    try:
        next(generator)
        return 0.01
    except StopIteration:
        pass
    except Exception as e:  # the check's own failure: reported, and Blender still quits
        say("failed", f"{type(e).__name__}: {e}")
    bpy.ops.wm.quit_blender()
    return None


bpy.app.timers.register(tick, first_interval=0.5)
