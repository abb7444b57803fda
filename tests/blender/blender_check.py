#!/usr/bin/env python3
"""The Blender add-on's checks (ctest label "blender"), each a headless Blender run with the
add-on loaded from src/blender. Usage: blender_check.py CHECK, one of:

identity: the add-on's F12 image equals, bit for bit, `mirage render` of the scene it exports.
cycles:   Cycles renders the same .blend; per colour channel the mean over the volume's pixels
          agrees within 5 %, and the silhouettes (alpha > 0.5) overlap with IoU >= 0.95: the
          check of the transform, Z-up and the light units (docs/blender.md, "Units").
reports:  a missing cache file is an error report and no image; a node Mirage cannot
          translate is one warning, and an image.
install:  pipeline/install-blender-addon.sh into a temporary Blender user folder, then a farm
          node's `blender -b FILE.blend -E MIRAGE -f 1` writes the frame.
physics:  every Mirage-only physics of the material panel on (chlorophyll with its
          fluorescence, CDOM from it, the medium's fluorescence, the index from temperature):
          the exported shader and [refraction] hold them, and the image is `mirage render`'s.
passes:   a render with every pass Mirage fills and three light groups, written by Blender as a
          multilayer EXR: the passes are there, the light passes (Emit, VolumeDir, VolumeInd)
          sum to Combined, so do the light groups, and the group without lights is black.
animation: a Mantaflow smoke domain baked for frames 1-6 (16 cells, OpenVDB data cache),
          rendered by a farm node's `-a` (frames 3 and 6): each frame's EXR names its own cache
          file in its metadata and the smoke has grown; frame 6 against Cycles (which reads the
          same cache through the Fluid modifier), as `cycles` does: the domain's placement;
          frame 6 with Motion Blur (Center): the domain's velocity exported, the image differs
          from the still one and is `mirage render`'s; frame 6 without its cache file: one
          error report naming it, no image.
surfaces: make_scene.py's --surfaces (a floor under the smoke, a mirror, a glass ball, a
          holdout): the exported materials and holdout, the image is `mirage render`'s bit for
          bit, and the floor is lit.
motion:   make-asset's smoke (its `vel` grid) as the test scene's volume, Velocity Grid set:
          with Render › Motion Blur (Center, Start) the exported shutter is Blender's, the
          velocity per second, the image differs from the still one and is `mirage render`'s.
viewport: Blender with a window under Xvfb (xvfb-run, Mesa's software OpenGL), the 3D viewport
          in Rendered shading: the screenshot is the session's image through the view transform
          and shows the smoke; a light's edit restarts the session (an update, passes from 1),
          so do edits of the material, its Mirage physics and the camera; a light added makes a
          new session.

Environment: MIRAGE_BINARY (the mirage command), PYTHONPATH (the built module), BLENDER
(default: blender on PATH). Exits 77 (ctest's skip) with a message when Blender is missing.
"""
import fcntl
import functools
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import tomllib

import numpy as np

import mirage

HERE = os.path.dirname(os.path.abspath(__file__))
OCIO = os.path.join(HERE, "..", "..", "src", "blender", "mirage_blender", "ocio", "config.ocio")
MIRAGE = os.environ.get("MIRAGE_BINARY", "mirage")
SAMPLES = 32          # both renderers; single scattering (Cycles: 0 volume bounces)
MEAN_TOLERANCE = 0.05
IOU_MIN = 0.95
SMOKE_IOU_MIN = 0.9   # the baked smoke: 16 cells across, its edge a few pixels of the frame
# The viewport's pixels against the render's through the sRGB encoding: the texture's half
# floats, the OCIO shader and the screenshot's 8 bits (3/255).
DRAWN_TOLERANCE = 3.0 / 255.0


def blender():
    exe = os.environ.get("BLENDER") or shutil.which("blender")
    if not exe:
        print("skipped: Blender is not installed (pipeline/install-deps.sh)")
        sys.exit(77)
    return exe


def run_blender(exe, script, *args, fails=False):
    """Blender, headless, on factory settings (not the user's add-ons or preferences). With
    `fails`, the run must exit non-zero: a render's error report makes --python-exit-code's
    Blender exit 1, as a farm node needs."""
    cmd = [exe, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
           os.path.join(HERE, script), "--", *args]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ,
                       MIRAGE_PYTHON_DIR=os.environ.get("PYTHONPATH", "").split(os.pathsep)[0]))
    if (p.returncode != 0) != fails:
        sys.exit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    return p.stdout


def lines(out, tag):
    return [l[len(tag) + 1:] for l in out.splitlines() if l.startswith(tag + " ")]


def make_blend(exe, folder, *flags):
    """The test scene: make-asset's fog sphere at 96 voxels per 2 m (fine enough that the half
    voxel by which Cycles places grids apart from OpenVDB's voxel centres stays a fifth of a
    pixel), as make_scene.py arranges it. Made once for every check that runs with the same
    scene scripts and mirage binary, in MIRAGE_BLENDER_SCENES (the build's folder; else in
    `folder`), under a lock: ctest may run the checks at once."""
    shared = os.environ.get("MIRAGE_BLENDER_SCENES")
    if not shared:
        return build_blend(exe, folder, flags)
    key = hashlib.sha1(repr(flags).encode())
    for path in (os.path.join(HERE, "make_scene.py"), os.path.join(HERE, "stage.py")):
        with open(path, "rb") as f:
            key.update(f.read())
    binary = os.stat(shutil.which(MIRAGE) or MIRAGE)
    key.update(f"{binary.st_size} {binary.st_mtime_ns}".encode())
    scenes = os.path.join(shared, key.hexdigest()[:16])
    os.makedirs(scenes, exist_ok=True)
    with open(os.path.join(scenes, "lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        return build_blend(exe, scenes, flags)


def build_blend(exe, folder, flags):
    """make_blend's scene in `folder`, unless it is there already."""
    blend = os.path.join(folder, "scene" + "".join(f.replace("--", "_") for f in flags) + ".blend")
    if os.path.exists(blend):
        return blend
    vdb = os.path.join(folder, "fog.vdb")
    if not os.path.exists(vdb):
        subprocess.run([MIRAGE, "make-asset", "fog-sphere", "--resolution", "96", "-o", vdb],
                       check=True, capture_output=True)
    run_blender(exe, "make_scene.py", vdb, blend, *flags)
    return blend


def render_as_exported(exe, folder, *flags, scene_flags=(), blend=None):
    """The add-on's image of `blend` (default: the test scene made with make_scene.py's
    `scene_flags`), and the scene it exported (TOML, parsed): the image must equal
    `mirage render` of that scene bit for bit."""
    blend = blend or make_blend(exe, folder, *scene_flags)
    addon_exr = os.path.join(folder, "addon.exr")
    toml = os.path.join(folder, "export", "scene.toml")
    out = run_blender(exe, "render_blend.py", blend, addon_exr, "mirage", "8", "--export", toml,
                      *flags)
    assert lines(out, "RESULT") == ["FINISHED written"], out
    cli_exr = os.path.join(folder, "cli.exr")
    # The frame seeds the samples: the CLI renders the frame the add-on rendered.
    frame = flags[flags.index("--frame") + 1] if "--frame" in flags else "1"
    subprocess.run([MIRAGE, "render", toml, "--ocio", OCIO, "-o", cli_exr, "--quiet",
                    "--frame", frame], check=True, capture_output=True)
    a, b = mirage.read(addon_exr).beauty, mirage.read(cli_exr).beauty
    assert a.shape == b.shape == (64, 48, 4), (a.shape, b.shape)
    assert a[..., 3].max() > 0.5, "the volume is not in the frame"
    differ = int(np.count_nonzero(a != b))
    assert differ == 0, f"{differ} values differ; largest difference {np.abs(a - b).max()}"
    with open(toml, "rb") as f:
        return a, tomllib.load(f)


def check_identity(exe, folder):
    a, _ = render_as_exported(exe, folder)
    print(f"identity: ok (64x48 RGBA, bit for bit; alpha mean {a[..., 3].mean():.4f})")


def check_physics(exe, folder):
    a, scene = render_as_exported(exe, folder, "--physics")
    volume = scene["volume"][0]
    with open(volume["shader"], "rb") as f:
        components = tomllib.load(f)["component"]
    density = volume["density_scale"]
    kinds = {c.get("kind", "linear"): c for c in components}
    assert set(kinds) == {"linear", "chlorophyll", "cdom"}, components
    close = functools.partial(np.isclose, rtol=1e-6)  # Blender's float properties are float32
    assert close(kinds["linear"]["quantum_efficiency"], 0.3), components
    assert close(kinds["linear"]["emission_peak_nm"], 520.0), components
    # 4 mg/m³ where the density attribute is 1, through Mirage's density_scale multiplier.
    assert close(kinds["chlorophyll"]["concentration"] * density, 4.0), (components, density)
    assert close(kinds["chlorophyll"]["quantum_efficiency"], 0.02), components
    assert kinds["cdom"]["covaries_with"] == "chlorophyll", components
    refraction = scene["refraction"]
    assert refraction["profile"] == "grid" and refraction["volume"] == 0, refraction
    assert close(refraction["ambient"], 288.15), refraction
    print(f"physics: ok (components {sorted(kinds)}, [refraction] {refraction}; "
          f"bit for bit as exported, alpha mean {a[..., 3].mean():.4f})")


def check_surfaces(exe, folder):
    a, scene = render_as_exported(exe, folder, scene_flags=("--surfaces",))
    materials = {m["name"]: m for m in scene["material"]}
    shapes = {s["name"]: s for s in scene["shape"]}
    assert set(shapes) == {"Floor", "Mirror", "Glass", "Holdout"}, shapes
    kinds = {n: materials[s["material"]]["type"] for n, s in shapes.items()}
    assert kinds == {"Floor": "diffuse", "Mirror": "mirror", "Glass": "dielectric",
                     "Holdout": "diffuse"}, kinds
    close = functools.partial(np.allclose, rtol=1e-6)  # Blender's float32 properties
    assert close(materials[shapes["Floor"]["material"]]["reflectance"], [0.6, 0.5, 0.4])
    assert close(materials[shapes["Glass"]["material"]]["ior"], 1.45)
    assert [n for n, s in shapes.items() if s.get("holdout")] == ["Holdout"], shapes
    # The floor fills the frame's bottom rows (rows top to bottom): opaque and lit there,
    # except where the holdout cube stands in front of it (black, zero alpha).
    bottom = a[-10:]
    floor = bottom[..., 3] > 0.999
    assert np.count_nonzero(floor) > 0.5 * floor.size, "the floor is not in the frame"
    assert np.all(bottom[floor][:, :3].max(axis=1) > 0.0), "unlit floor pixels"
    held = a[..., 3] == 0.0
    assert np.count_nonzero(held & (a[..., :3].max(axis=2) == 0.0)) > 0
    print(f"surfaces: ok (materials {kinds}; floor mean RGB "
          f"{np.round(bottom[floor][:, :3].mean(axis=0), 4).tolist()} on {np.count_nonzero(floor)} "
          f"of the bottom rows' pixels; bit for bit as exported)")


def check_motion(exe, folder):
    vdb = os.path.join(folder, "smoke.vdb")
    subprocess.run([MIRAGE, "make-asset", "smoke", "--resolution", "32", "-o", vdb],
                   check=True, capture_output=True)
    still, scene = render_as_exported(exe, folder, "--velocity", vdb)
    assert "shutter" not in scene["camera"], scene["camera"]
    shutters, differ = {}, {}
    for position in ("CENTER", "START"):
        blurred, scene = render_as_exported(exe, folder, "--velocity", vdb, "--blur", position)
        shutters[position] = scene["camera"]["shutter"]
        volume = scene["volume"][0]
        # 0.5 of the file's units per frame, at Blender's default 24 frames per second.
        assert volume["velocity"] == "vel" and scene["output"]["fps"] == 24.0, scene
        assert np.isclose(volume["velocity_scale"], 12.0), volume
        differ[position] = float(np.abs(blurred - still).max())
        assert differ[position] > 0.01, f"{position}: the blurred image equals the still one"
    assert shutters == {"CENTER": [-0.25, 0.25], "START": [0.0, 0.5]}, shutters
    print(f"motion: ok (shutters {shutters}; largest difference from the still render "
          f"{differ}; bit for bit as exported)")


def check_cycles(exe, folder):
    blend = make_blend(exe, folder)
    exrs = {}
    for engine in ("mirage", "cycles"):
        exrs[engine] = os.path.join(folder, engine + ".exr")
        out = run_blender(exe, "render_blend.py", blend, exrs[engine], engine, str(SAMPLES),
                          "--integrator", "single")
        assert lines(out, "RESULT") == ["FINISHED written"], out
    print("cycles: ok (" + compare_with_cycles(exrs["mirage"], exrs["cycles"], IOU_MIN) + ")")


def check_reports(exe, folder):
    missing = make_blend(exe, folder, "--missing-cache")
    exr = os.path.join(folder, "missing.exr")
    out = run_blender(exe, "render_blend.py", missing, exr, "mirage", "4", fails=True)
    errors = [r for r in lines(out, "REPORT") if r.startswith("ERROR")]
    assert len(errors) == 1 and "does not exist" in errors[0] and "Smoke" in errors[0], out
    assert not os.path.exists(exr) and lines(out, "RESULT")[0].endswith("no-file"), out
    node = make_blend(exe, folder, "--node-extra")
    exr = os.path.join(folder, "node.exr")
    out = run_blender(exe, "render_blend.py", node, exr, "mirage", "4")
    warnings = [r for r in lines(out, "REPORT") if "material nodes left out" in r]
    assert len(warnings) == 1 and "Density Boost" in warnings[0], out
    assert lines(out, "RESULT") == ["FINISHED written"], out
    assert mirage.read(exr).beauty[..., 3].max() > 0.5, "the warned render is empty"
    print(f"reports: ok ({errors[0]!r}; {warnings[0]!r})")


def check_install(exe, folder):
    blend = make_blend(exe, folder)
    env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(folder, "user", "scripts"),
               BLENDER_USER_CONFIG=os.path.join(folder, "user", "config"))
    build = os.path.dirname(os.environ["PYTHONPATH"].split(os.pathsep)[0])
    script = os.path.join(HERE, "..", "..", "pipeline", "install-blender-addon.sh")
    p = subprocess.run([script, build], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    frame = os.path.join(folder, "farm_0001.exr")
    p = subprocess.run([exe, "-b", blend, "-E", "MIRAGE", "-o", os.path.join(folder, "farm_####"),
                        "-F", "OPEN_EXR", "-f", "1"], capture_output=True, text=True, env=env)
    assert p.returncode == 0 and os.path.isfile(frame), p.stdout + p.stderr
    alpha = mirage.read(frame).beauty[..., 3].max()
    assert alpha > 0.5, "the farm frame is empty"
    print(f"install: ok (the installed add-on rendered {os.path.basename(frame)}, alpha max {alpha:.3f})")


def check_passes(exe, folder):
    blend = make_blend(exe, folder)
    exr = os.path.join(folder, "passes.exr")
    out = run_blender(exe, "render_blend.py", blend, exr, "mirage", "8", "--passes")
    assert lines(out, "RESULT") == ["FINISHED written"], out
    layers = {k.split(".", 1)[1]: v for k, v in mirage.read(exr).aovs.items()}
    expected = {"Combined", "Depth", "Emit", "VolumeDir", "VolumeInd", "Albedo", "Transmittance",
                "Combined_key", "Combined_sky", "Combined_rim"}
    assert set(layers) == expected, sorted(layers)
    combined = layers["Combined"][..., :3].astype(np.float64)
    errors = []
    # The light paths, and the light groups (every light is in one; nothing emits).
    for parts in (("Emit", "VolumeDir", "VolumeInd"), ("Combined_key", "Combined_sky")):
        total = sum(layers[n].astype(np.float64) for n in parts)
        errors.append(np.abs(total - combined).max())
        # Float rounding: float32 passes summed against their float32 total.
        assert errors[-1] <= 1e-6 * max(1.0, combined.max()), f"{parts} sum off by {errors}"
    assert layers["Combined_key"].max() > 0.1 and layers["Combined_sky"].max() > 0.01, "empty"
    assert not layers["Combined_rim"].any(), "a light group without lights is not black"
    assert layers["VolumeDir"].max() > 0.1 and layers["VolumeInd"].max() > 0.01, "empty passes"
    depth, alpha = layers["Depth"][..., 0], layers["Combined"][..., 3]
    assert np.all(np.isfinite(depth)) and depth[alpha > 0.9].max() < 10.0, "depth of the smoke"
    # The background (a few fringe pixels hold a depth from the depth pass's own walk).
    background = depth[alpha == 0.0]
    assert np.mean(background == np.float32(1.0e10)) > 0.9, "the background's depth is not 1e10"
    print(f"passes: ok ({', '.join(sorted(layers))}; light paths and light groups sum to "
          f"Combined within {errors[0]:.2e} and {errors[1]:.2e})")


def compare_with_cycles(mirage_exr, cycles_exr, iou_min):
    """The silhouettes' (alpha > 0.5) IoU and the ratio of the channel means over the smoke."""
    m, c = (mirage.read(f).beauty.astype(np.float64) for f in (mirage_exr, cycles_exr))
    sm, sc = m[..., 3] > 0.5, c[..., 3] > 0.5
    iou = np.count_nonzero(sm & sc) / max(np.count_nonzero(sm | sc), 1)
    smoke = (m[..., 3] > 0.02) | (c[..., 3] > 0.02)
    ratio = m[smoke, :3].mean(axis=0) / c[smoke, :3].mean(axis=0)
    report = (f"silhouette IoU {iou:.4f} ({np.count_nonzero(sm)} / {np.count_nonzero(sc)} "
              f"pixels), mean RGB Mirage / Cycles {np.round(ratio, 4).tolist()}")
    assert iou >= iou_min, f"silhouette IoU {iou:.4f} below {iou_min}: {report}"
    assert np.all(np.abs(ratio - 1.0) <= MEAN_TOLERANCE), f"channel means differ: {report}"
    return report


def check_animation(exe, folder):
    blend = os.path.join(folder, "smoke.blend")
    run_blender(exe, "make_smoke.py", os.path.join(folder, "cache"), blend)
    single = ("import bpy; s = bpy.context.scene; s.mirage.integrator = 'single'; "
              f"s.mirage.samples = {SAMPLES}")
    p = subprocess.run([exe, "-b", blend, "--factory-startup", "--python",
                        os.path.join(HERE, "addon_from_source.py"), "--python-expr", single,
                        "-E", "MIRAGE", "-o", os.path.join(folder, "anim_####"),
                        "-F", "OPEN_EXR", "-a"],
                       capture_output=True, text=True, env=dict(os.environ, MIRAGE_PYTHON_DIR=(
                           os.environ.get("PYTHONPATH", "").split(os.pathsep)[0])))
    frames = {f: os.path.join(folder, f"anim_{f:04d}.exr") for f in (3, 6)}
    assert p.returncode == 0 and all(map(os.path.isfile, frames.values())), p.stdout + p.stderr
    images = {}
    for f, exr in frames.items():
        image = mirage.read(exr)
        files = image.metadata.get("mirage:volume_files", "")
        assert os.path.basename(files) == f"fluid_data_{f:04d}.vdb", (f, files)
        images[f] = image.beauty
    covered = {f: np.count_nonzero(image[..., 3] > 0.5) for f, image in images.items()}
    assert covered[6] > 1.15 * covered[3], f"the smoke did not grow from frame 3 to 6: {covered}"
    cycles = os.path.join(folder, "cycles.exr")
    out = run_blender(exe, "render_blend.py", blend, cycles, "cycles", str(SAMPLES),
                      "--integrator", "single", "--frame", "6")
    assert lines(out, "RESULT") == ["FINISHED written"], out
    report = compare_with_cycles(frames[6], cycles, SMOKE_IOU_MIN)
    # Motion blur: the domain's cached velocity (per second) with its Velocity Scale.
    still, _ = render_as_exported(exe, folder, "--frame", "6", blend=blend)
    blurred, scene = render_as_exported(exe, folder, "--frame", "6", "--blur", "CENTER",
                                        blend=blend)
    volume = scene["volume"][0]
    assert (volume["velocity"], volume["velocity_scale"]) == ("velocity", 1.0), volume
    assert scene["camera"]["shutter"] == [-0.25, 0.25], scene["camera"]
    blur = float(np.abs(blurred - still).max())
    assert blur > 0.01, "the blurred frame equals the still one"
    # A frame whose cache file is gone: one error report naming the domain and the file.
    os.remove(os.path.join(folder, "cache", "data", "fluid_data_0006.vdb"))
    missing = os.path.join(folder, "missing.exr")
    out = run_blender(exe, "render_blend.py", blend, missing, "mirage", "4", "--frame", "6",
                      fails=True)
    errors = [r for r in lines(out, "REPORT") if r.startswith("ERROR")]
    assert len(errors) == 1 and "Smoke Domain" in errors[0] and \
        "fluid_data_0006.vdb" in errors[0] and not os.path.exists(missing), out
    print(f"animation: ok (frames 3 and 6 read fluid_data_0003.vdb and fluid_data_0006.vdb; "
          f"alpha > 0.5 on {covered[3]} and {covered[6]} pixels; frame 6 against Cycles: "
          f"{report}; blurred by its velocity, largest difference {blur:.3f}, bit for bit as "
          f"exported; without its file: {errors[0]!r})")


def check_viewport(exe, folder):
    xvfb = shutil.which("xvfb-run")
    if not xvfb:
        print("skipped: xvfb-run is not installed (pipeline/install-deps.sh: xvfb)")
        sys.exit(77)
    blend = make_blend(exe, folder)
    # Blender's smallest window; viewport_blend.py renders a quarter of its 3D viewport.
    cmd = [xvfb, "-a", "-s", "-screen 0 640x480x24", exe, blend, "--factory-startup",
           "--python", os.path.join(HERE, "viewport_blend.py"), "--",
           os.path.join(folder, "viewport.png")]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=240, env=dict(
        os.environ, MIRAGE_PYTHON_DIR=os.environ.get("PYTHONPATH", "").split(os.pathsep)[0]))
    record = dict(l.split(" ", 1) for l in lines(p.stdout, "VIEWPORT"))
    assert record.get("done") == "ok", f"{' '.join(cmd)}:\n{p.stdout}\n{p.stderr}"
    assert record["error"] == "none", record
    shot, drawn = record["shape"].split()
    assert shot == drawn, f"the screenshot ({shot}) is not the render's size ({drawn})"
    assert float(record["drawn_error_p95"]) < DRAWN_TOLERANCE, record
    assert int(record["smoke_pixels"]) > 100, record
    assert float(record["smoke_contrast"]) > 0.05, record
    assert int(record["restarts_after_edit"]) == int(record["restarts_before_edit"]) + 1, record
    assert record["update_kind"] == "update", record
    assert int(record["passes_after_edit"]) < int(record["passes_before_edit"]), record
    for what in ("material", "physics", "camera"):
        assert record[f"{what}_edit"].split()[0] == "update", record
    assert record["added_light_kind"] == "new", record
    print("viewport: ok (" + ", ".join(f"{k} {v}" for k, v in record.items()) + ")")


def main():
    checks = {"identity": check_identity, "cycles": check_cycles, "reports": check_reports,
              "install": check_install, "passes": check_passes, "animation": check_animation,
              "physics": check_physics, "viewport": check_viewport,
              "surfaces": check_surfaces, "motion": check_motion}
    if len(sys.argv) != 2 or sys.argv[1] not in checks:
        sys.exit(__doc__)
    exe = blender()
    with tempfile.TemporaryDirectory(prefix="mirage-blender-test-") as folder:
        checks[sys.argv[1]](exe, folder)


if __name__ == "__main__":
    main()
