"""The render engine Blender calls for F12, `-f` and `-a` (bl_idname "MIRAGE"): the scene
exported (export.py), rendered by a mirage.Session in passes, each pass shown, the last one
written into Blender's render result in its scene-linear space (docs/blender.md)."""
import tempfile
import threading

import bpy
import numpy as np

from . import export, module_path

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
    # Material Preview viewport: the add-on has no viewport render of its own yet.
    bl_use_shading_nodes_custom = False
    bl_use_eevee_viewport = True

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
                self._render(mirage, m_scene, settings, scene)
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

    def _render(self, mirage, m_scene, settings, scene):
        """The render in passes: each pass into the result as it comes, the last one kept."""
        w, h = export.resolution(scene)
        opaque = not scene.render.film_transparent
        last = None
        with mirage.Session(m_scene, **settings.render_arguments()) as session:
            with _BreakWatch(self, session):
                for image in session:
                    last = image
                    self._show(image, w, h, opaque, final=False)
                    self.update_stats("", f"Mirage | pass {image.metadata.get('mirage:passes')}")
            if self.test_break():
                return
            final = session.result or last
        if final is not None:
            self._show(final, w, h, opaque, final=True)

    def _show(self, image, w, h, opaque, final):
        """Pixels into the render result: Blender's rows run bottom to top, Mirage's top to
        bottom; an opaque film (not Film › Transparent) has alpha 1, as Cycles gives it."""
        pixels = np.ascontiguousarray(np.flipud(image.beauty), dtype=np.float32).reshape(-1, 4)
        if opaque:
            pixels[:, 3] = 1.0
        result = self.begin_result(0, 0, w, h)
        try:
            result.layers[0].passes["Combined"].rect = pixels
            if not final:
                self.update_result(result)
        finally:
            # A pass shown is not the frame: cancel=True keeps it out of the saved image.
            self.end_result(result, cancel=not final)
