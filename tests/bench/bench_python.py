#!/usr/bin/python3
"""The Python module's speed against the mirage command (issue 35's three figures):
  1. the overhead of a finished render through mirage.render against `mirage render` of the same
     scene and settings (the whole command, process start and EXR write included; the Python
     side times load + render + Image.write, the import excluded);
  2. the time from a Session's start to its first image;
  3. the time from Session.update() to the next image
(2 and 3 with a time limit, so that the first image is the coarse image, as a viewport wants).
Runs each RUNS times interleaved and prints medians. Usage (from the repository root, after
pipeline/build.sh build):
  PYTHONPATH=build/python /usr/bin/python3 tests/bench/bench_python.py [SCENE] [--spp N] [--runs N]
SCENE defaults to the demo (assets/scenes/demo.toml; pipeline/demo.sh makes its cache)."""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import mirage


def cli_seconds(binary, scene, spp, out):
    t0 = time.perf_counter()
    # No preview: Image.write writes the EXR alone.
    subprocess.run([binary, "render", scene, "--spp", str(spp), "--seed", "1", "--quiet",
                    "--set", "output.preview=", "-o", out], check=True,
                   stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def python_seconds(scene, spp, out):
    t0 = time.perf_counter()
    image = mirage.render(mirage.load(scene, set={"output.preview": ""}), spp=spp, seed=1)
    image.write(out)
    return time.perf_counter() - t0


def session_seconds(scene, spp):
    """(start → first image, update() → next image) of one interactive session: with a time
    limit, whose first image is the coarse image, as a viewport asks."""
    s = mirage.load(scene)
    t0 = time.perf_counter()
    with mirage.Session(s, spp=spp, seed=1, time_limit=60.0) as session:
        next(session)
        first = time.perf_counter() - t0
        t1 = time.perf_counter()
        session.update({"camera.fov": float(s.info()["camera"]["fov"]) * 0.9})
        next(session)
        return first, time.perf_counter() - t1


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene", nargs="?", default="assets/scenes/demo.toml")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--mirage", default="build/mirage")
    a = ap.parse_args()
    cli, py, first, edit = [], [], [], []
    with tempfile.TemporaryDirectory() as d:
        for _ in range(a.runs):
            cli.append(cli_seconds(a.mirage, a.scene, a.spp, os.path.join(d, "cli.exr")))
            py.append(python_seconds(a.scene, a.spp, os.path.join(d, "py.exr")))
            f, e = session_seconds(a.scene, a.spp)
            first.append(f)
            edit.append(e)
    c, p = statistics.median(cli), statistics.median(py)
    print(f"scene {a.scene}, {a.spp} spp, {a.runs} runs each (medians)")
    print(f"  mirage render (whole command): {c:.3f} s   {[round(x, 3) for x in cli]}")
    print(f"  mirage.render + write:         {p:.3f} s   {[round(x, 3) for x in py]}")
    print(f"  Python / command:              {p / c:.3f}")
    print(f"  session start -> first image:  {statistics.median(first):.3f} s")
    print(f"  update() -> next image:        {statistics.median(edit):.3f} s")


if __name__ == "__main__":
    sys.exit(main())
