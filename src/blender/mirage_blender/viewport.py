"""The viewport's render (Rendered shading): a mirage.Session refining in the background, restarted
after each edit. The engine (engine.py) exports the scene with the viewport's camera on Blender's
main thread and submits the document here; a worker thread owns the session, takes each pass's
image, and the engine draws the latest one. An edit that only changes values the scene already
has (a light's power, a camera, a volume's file at another frame, a material, which is a new
shader file) is a `Session.update` of those keys, which keeps the grids read; anything else (an
object added or removed) is a new Session (docs/blender.md, "Viewport")."""
import tempfile
import threading
import time

import numpy as np
from . import export

# What the viewports rendered, for the tests and the measurements in docs/blender.md: the
# restarts so far, the passes of the image shown, the seconds from a submit to its first image.
RECORD = {"restarts": 0, "last_restart": "", "passes": 0, "images": 0, "first_image_seconds": [],
          "error": ""}
LIVE = []  # the ViewportRenders running, one per viewport in Rendered shading


def view_camera(region, region_data, pixel_size):
    """The viewport's [camera] and [film] resolution: its view matrix (world to view) inverted
    is a camera-to-world matrix like a camera object's; a perspective window matrix has
    1 / tan(half the vertical angle) in its [1][1]. An orthographic view has no angle: it
    renders as a 50 mm lens on a 36 mm sensor would."""
    m = region_data.view_matrix.inverted()
    wm = region_data.window_matrix
    tan_half = 1.0 / wm[1][1] if region_data.is_perspective and wm[1][1] > 0.0 else 18.0 / 50.0
    w = max(1, region.width // pixel_size)
    h = max(1, region.height // pixel_size)
    return export.camera_from_matrix(m, tan_half), (w, h)


# A restart's first image is a coarse one, a quarter of the resolution each way at one sample
# per pixel (a sixteenth of a pass's cost), where the viewport has more pixels than this; the
# session then goes on at full resolution. Blender stretches the coarse image over the region.
COARSE_ABOVE_PIXELS = 128 * 128
COARSE_DIVISOR = 4


def coarse_and_full(film):
    """The `--set` keys of a restart's coarse image (None where the viewport is small) and of
    the full render after it."""
    w, h = film["resolution"]
    full = {"film.resolution": [w, h], "film.spp": film["spp"]}
    if w * h <= COARSE_ABOVE_PIXELS:
        return None, full
    coarse = [-(-w // COARSE_DIVISOR), -(-h // COARSE_DIVISOR)]
    return {"film.resolution": coarse, "film.spp": 1}, full


def flatten(doc, prefix=""):
    """The document's leaves as the dotted keys `--set` takes: tables by name, arrays of tables
    (`volume`, `light`) by index, other arrays (a position) as one value."""
    out = {}
    items = doc.items() if isinstance(doc, dict) else enumerate(doc)
    for k, v in items:
        key = f"{prefix}{k}"
        if isinstance(v, dict) or (isinstance(v, list) and v and isinstance(v[0], dict)):
            out.update(flatten(v, key + "."))
        else:
            out[key] = v
    return out


def plan(before, after):
    """The `--set` keys that turn the document `before` into `after`, or None when they differ
    in which keys they hold (an object added or removed: a new session)."""
    if before is None:
        return None
    a, b = flatten(before), flatten(after)
    if a.keys() != b.keys():
        return None
    return {k: v for k, v in b.items() if a[k] != v}


class ViewportRender:
    """The worker thread and its session. The main thread submits documents; the worker applies
    them between passes and publishes each pass's image (rows bottom to top, as a texture
    wants). Only the worker calls the session's update; the main thread only cancels it, and
    only when the worker is not inside an update, so no two threads stop it at once."""

    def __init__(self, mirage):
        self.mirage = mirage
        self.folder = tempfile.TemporaryDirectory(prefix="mirage-viewport-")
        self.doc = None             # the last document submitted
        self.kwargs = None
        self.pending = None         # ("new", doc, kwargs, frame) or ("update", {key: value})
        self.submitted_at = 0.0
        self.session = None
        self.refine = None          # the full render's keys while the coarse image renders
        self.session_lock = threading.Lock()  # held by the worker while it changes the session
        self.pending_lock = threading.Lock()
        self.wake = threading.Event()
        self.stopping = False
        self.pixels = None          # the latest image, float32 height x width x 4
        self.serial = 0             # images published so far
        self.drawn = None           # the pixels the engine's texture holds (for the tests)
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()
        LIVE.append(self)

    def submit(self, doc, kwargs, frame):
        """Restarts the render on `doc` (an update where plan() finds one), if it changed."""
        changes = plan(self.doc, doc) if kwargs == self.kwargs else None
        if changes == {}:
            return
        self.doc, self.kwargs = doc, kwargs
        with self.pending_lock:
            if changes is None or (self.pending and self.pending[0] == "new"):
                self.pending = ("new", doc, kwargs, frame)
            elif self.pending:
                self.pending = ("update", {**self.pending[1], **changes})
            else:
                self.pending = ("update", changes)
            self.submitted_at = time.perf_counter()
        self._interrupt()

    def fail(self, message):
        """An export that failed: no render until the next submit succeeds."""
        self.doc = None
        with self.pending_lock:
            self.pending = ("error", message)
        self._interrupt()

    def _interrupt(self):
        """Stops the pass in flight so the worker takes the pending edit now; if the worker is
        changing the session it takes the edit right after, with no cancel needed."""
        self.wake.set()
        if self.session_lock.acquire(blocking=False):
            try:
                if self.session is not None:
                    self.session.cancel()
            finally:
                self.session_lock.release()

    def stop(self):
        self.stopping = True
        self._interrupt()
        self.thread.join()
        self.session = None
        self.folder.cleanup()
        LIVE.remove(self)

    def _run(self):
        started = None  # when the edit whose first image is awaited was submitted
        while not self.stopping:
            with self.pending_lock:
                command, self.pending = self.pending, None
                since = self.submitted_at
            if command is not None:
                with self.session_lock:
                    self._apply(command)
                started = since
            image = self._next()
            if image is None:
                if self.pending is None and not self.stopping:
                    self.wake.wait()
                self.wake.clear()
                continue
            self._publish(image, started)
            started = None
            if self.refine is not None and self.pending is None:
                with self.session_lock:
                    self._refine()

    def _apply(self, command):
        """A command from submit() on the session, on the worker (grid files load here)."""
        RECORD["error"] = ""
        self.refine = None
        try:
            if command[0] == "error":
                self.session = None
                RECORD["error"] = command[1]
                return
            coarse, full = coarse_and_full(self.doc["film"])
            if command[0] == "update" and self.session is not None:
                self.session.update({**command[1], **(coarse or full)})
            else:
                self.session = None
                _, doc, kwargs, frame = command
                scene = self.mirage.Scene.from_dict(doc, set=coarse or {},
                                                    base_dir=self.folder.name,
                                                    ocio=export.OCIO_CONFIG, frame=frame)
                self.session = self.mirage.Session(scene, **kwargs)
            self.refine = full if coarse else None
            RECORD["restarts"] += 1
            RECORD["last_restart"] = command[0]
            RECORD["passes"] = 0
        except self.mirage.Error as e:
            self.session = None
            RECORD["error"] = f"Mirage: {e}"

    def _refine(self):
        """After the coarse image: the full resolution and samples, the grids kept."""
        keys, self.refine = self.refine, None
        try:
            self.session.update(keys)
        except self.mirage.Error as e:
            self.session = None
            RECORD["error"] = f"Mirage: {e}"

    def _next(self):
        """The session's next image of its current generation; None when it has stopped."""
        session = self.session
        if session is None:
            return None
        try:
            while True:
                image = next(session)
                if image.generation == session.generation:
                    return image
        except StopIteration:
            return None
        except self.mirage.Error as e:
            RECORD["error"] = f"Mirage: {e}"
            return None

    def _publish(self, image, started):
        self.pixels = np.ascontiguousarray(np.flipud(image.beauty), dtype=np.float32)
        RECORD["passes"] = int(image.metadata.get("mirage:passes", "0"))
        RECORD["images"] += 1
        if started is not None:
            RECORD["first_image_seconds"].append(time.perf_counter() - started)
        self.serial += 1

