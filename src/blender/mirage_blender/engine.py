"""The render engine Blender calls for F12, `-f` and `-a` (bl_idname "MIRAGE"): the scene
exported (export.py), rendered by a mirage.Session in passes, each pass shown, the last one
written into Blender's render result in its scene-linear space (docs/blender.md); and for the
viewport's Rendered shading, a session refining in the background (viewport.py), drawn as a
texture through Blender's view transform."""
import functools
import tempfile
import threading
import weakref

import bpy
import gpu
import numpy as np
from gpu_extras.presets import draw_texture_2d

from . import export, module_path, passes, viewport

# What the last render reported, (type, message) pairs: Blender shows them in its status bar
# and prints them in the background; tests read them here.
REPORTS = []


def _preferred_dir(context):
    addon = context.preferences.addons.get(__package__) if context else None
    return addon.preferences.python_dir if addon else ""


class _BreakWatch:
    """Cancels the session when Blender asks the render to stop (Esc), checked every 50 ms on
    a thread of its own: a session waits for its next pass with Python's lock released."""

    def __init__(self, engine, session):
        self.stop = threading.Event()
        self.thread = threading.Thread(target=self._watch, args=(engine, session), daemon=True)

    def _watch(self, engine, session):
        while not self.stop.wait(0.05):
            if engine.test_break():
                session.cancel()
                return

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.stop.set()
        self.thread.join()
        return False


class MirageRenderEngine(bpy.types.RenderEngine):
    bl_idname = "MIRAGE"
    bl_label = "Mirage"
    bl_use_preview = False
    bl_use_postprocess = True
    # Blender's own shader nodes (the Principled Volume the export reads), and Eevee for the
    # Material Preview viewport; Rendered shading is Mirage's (view_update, view_draw).
    bl_use_shading_nodes_custom = False
    bl_use_eevee_viewport = True

    def __init__(self):
        self.stamp = {}          # metadata of F12's frame beside the image's own
        self.viewport = None     # the viewport's ViewportRender, made by the first view_update
        self.scene_doc = None    # the exported scene without camera and film
        self.texture = None
        self.texture_serial = -1
        self.shown_serial = -1

    def __del__(self):
        if getattr(self, "viewport", None) is not None:
            self.viewport.stop()

    def _report(self, kind, message):
        """A report to Blender, kept in REPORTS too (RNA's own `report` cannot be overridden:
        Blender looks its functions up before the Python class's)."""
        REPORTS.append((kind, message))
        self.report({kind}, message)

    def render(self, depsgraph):
        REPORTS.clear()
        scene = depsgraph.scene
        settings = scene.mirage
        with tempfile.TemporaryDirectory(prefix="mirage-blender-") as folder:
            try:
                mirage = module_path.import_mirage(_preferred_dir(bpy.context))
                ex = export.export(depsgraph, settings, folder)
                ex.write_shaders()
                self._warn(ex)
                m_scene = mirage.Scene.from_dict(ex.scene, base_dir=folder,
                                                 ocio=export.OCIO_CONFIG,
                                                 frame=scene.frame_current)
                self.stamp = {"mirage:volume_files": ";".join(
                    v["file"] for v in ex.scene.get("volume", []))}
                groups = {lt.get("group") for lt in ex.scene.get("light", [])}
                self._render(mirage, m_scene, settings, scene,
                             passes.lit(passes.enabled(depsgraph.view_layer), groups))
            except (ImportError, export.ExportError) as e:
                self._report("ERROR", f"Mirage: {e}")
            except Exception as e:  # a mirage.Error names the scene key, file and grid
                if type(e).__name__ != "Error":
                    raise
                self._report("ERROR", f"Mirage: {e}")

    def _warn(self, ex):
        """One warning for the material nodes left out, one for the other settings."""
        if ex.left_out_nodes:
            self._report("WARNING", "Mirage: material nodes left out (rendered with the "
                        "closest shader): " + "; ".join(ex.left_out_nodes))
        if ex.left_out:
            self._report("WARNING", "Mirage: not translated: " + "; ".join(ex.left_out))

    def update_render_passes(self, scene=None, renderlayer=None):
        passes.register_passes(self, scene, renderlayer)

    def _render(self, mirage, m_scene, settings, scene, chosen):
        """The render in passes: each pass into the result as it comes, the last one kept,
        with the view layer's render passes."""
        w, h = export.resolution(scene)
        opaque = not scene.render.film_transparent
        last = None
        arguments = settings.render_arguments()
        if chosen:
            arguments["aovs"] = [p.aov for p in chosen]
        with mirage.Session(m_scene, **arguments) as session:
            with _BreakWatch(self, session):
                for image in session:
                    last = image
                    self._show(image, w, h, opaque, final=False)
                    self.update_stats("", f"Mirage | pass {image.metadata.get('mirage:passes')}")
            if self.test_break():
                return
            final = session.result or last
        if final is not None:
            self._show(final, w, h, opaque, final=True, chosen=chosen)

    def _show(self, image, w, h, opaque, final, chosen=()):
        """Pixels into the render result: Blender's rows run bottom to top, Mirage's top to
        bottom; an opaque film (not Film › Transparent) has alpha 1, as Cycles gives it."""
        pixels = np.ascontiguousarray(np.flipud(image.beauty), dtype=np.float32).reshape(-1, 4)
        if opaque:
            pixels[:, 3] = 1.0
        result = self.begin_result(0, 0, w, h)
        try:
            result.layers[0].passes["Combined"].rect = pixels
            passes.write(result.layers[0], image, chosen)
            if final:
                self._stamp(image)
            if not final:
                self.update_result(result)
        finally:
            # A pass shown is not the frame: cancel=True keeps it out of the saved image.
            self.end_result(result, cancel=not final)

    def _stamp(self, image):
        """Mirage's record of the frame in Blender's metadata (an EXR's header): the files
        its volumes read, the integrator, samples and seed it rendered with. On the frame's
        whole result: a result from begin_result gives Blender its pixels, not its stamp."""
        result = self.get_result()
        fields = dict(self.stamp)
        for key in ("mirage:integrator", "mirage:spp", "mirage:seed", "mirage:version"):
            if key in image.metadata:
                fields[key] = image.metadata[key]
        for key, value in fields.items():
            result.stamp_data_add_field(key, value)

    # The viewport (Rendered shading). view_update follows every edit of the scene, view_draw
    # every redraw, a view rotated or zoomed included; both on Blender's main thread, which
    # must not wait for a pass: the session renders on the worker, a timer asks for a redraw
    # when a pass arrives.

    def view_update(self, context, depsgraph):
        if self.viewport is None:
            try:
                mirage = module_path.import_mirage(_preferred_dir(context))
            except ImportError as e:
                viewport.RECORD["error"] = f"Mirage: {e}"
                self.update_stats("", viewport.RECORD["error"])
                return
            self.viewport = viewport.ViewportRender(mirage)
            bpy.app.timers.register(functools.partial(_poll, weakref.ref(self)))
        try:
            ex = export.export(depsgraph, depsgraph.scene.mirage, self.viewport.folder.name,
                               scene_camera=False)
            ex.write_shaders()
            self.scene_doc = ex.scene
        except export.ExportError as e:
            self.scene_doc = None
            self.viewport.fail(f"Mirage: {e}")

    def view_draw(self, context, depsgraph):
        if self.viewport is None:
            return
        scene = depsgraph.scene
        if self.scene_doc is not None:
            self.viewport.submit(*_view_document(self.scene_doc, context, scene))
        self._draw_latest(context.region, scene)

    def _draw_latest(self, region, scene):
        """The latest pass as a texture over the region (the render may be at a coarser pixel
        size), in scene-linear: Blender's display space shader applies the view transform."""
        serial, pixels = self.viewport.serial, self.viewport.pixels
        if pixels is None:
            return
        if serial != self.texture_serial:
            h, w = pixels.shape[:2]
            self.viewport.drawn = pixels
            if not scene.render.film_transparent:
                # An opaque film covers the viewport, as F12's alpha of 1 covers the frame:
                # Blender lays the engine's premultiplied pixels over its own background.
                pixels = pixels.copy()
                pixels[..., 3] = 1.0
            data = gpu.types.Buffer("FLOAT", w * h * 4, pixels.ravel())
            self.texture = gpu.types.GPUTexture((w, h), format="RGBA16F", data=data)
            self.texture_serial = serial
        gpu.state.blend_set("ALPHA_PREMULT")
        self.bind_display_space_shader(scene)
        draw_texture_2d(self.texture, (0, 0), region.width, region.height)
        self.unbind_display_space_shader()
        gpu.state.blend_set("NONE")

    def _poll(self):
        """On Blender's main thread, every 50 ms: a redraw when a pass has arrived."""
        serial = self.viewport.serial
        if serial != self.shown_serial:
            self.shown_serial = serial
            self.update_stats("", viewport.RECORD["error"] or
                              f"Mirage | pass {viewport.RECORD['passes']}")
            self.tag_redraw()
        elif viewport.RECORD["error"]:
            self.update_stats("", viewport.RECORD["error"])


def _poll(engine_ref):
    """The timer of one viewport's engine: it ends when Blender frees the engine."""
    engine = engine_ref()
    if engine is None or engine.viewport is None:
        return None
    try:
        engine._poll()
    except ReferenceError:
        return None
    return 0.05


def _view_document(scene_doc, context, scene):
    """The viewport's scene document, session arguments and frame: the export with the view's
    camera, the region's pixels (divided by Blender's Viewport › Pixel Size), the viewport's
    samples in passes of one sample, so the first image comes after one sample per pixel."""
    settings = scene.mirage
    pixel_size = _pixel_size(context, scene)
    camera, (w, h) = viewport.view_camera(context.region, context.region_data, pixel_size)
    doc = dict(scene_doc, camera=camera,
               film={"resolution": [w, h], "spp": int(settings.preview_samples),
                     "seed": int(settings.seed)},
               render=dict(scene_doc["render"], pass_spp=1))
    return doc, {"threads": settings.threads}, scene.frame_current


def _pixel_size(context, scene):
    """Render › Performance › Viewport › Pixel Size: Automatic follows the display's scale."""
    size = scene.render.preview_pixel_size
    if size == "AUTO":
        return max(1, int(round(context.preferences.system.pixel_size)))
    return int(size)
