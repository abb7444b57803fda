"""Fixtures of the Python module's tests: the mirage command (to compare with), and a small fog
sphere scene made with `mirage make-asset` in a temporary folder. ctest sets PYTHONPATH to the
built package and MIRAGE_BINARY to the command (tests/CMakeLists.txt)."""
import os
import subprocess
import sys

import pytest

MIRAGE = os.environ.get("MIRAGE_BINARY", "mirage")

# The fog sphere of assets/scenes/fog_sphere.toml at a tiny size: 24x24 pixels, 4 samples of
# the path tracer.
FOG_SCENE = {
    "film": {"resolution": [24, 24], "spp": 4, "seed": 1},
    "render": {"integrator": "volpath"},
    "camera": {"position": [0.0, 1.0, 3.2], "look_at": [0.0, 1.0, 0.0], "fov": 40.0},
    "volume": [{"file": "fog_sphere.vdb", "shader": "smoke", "density_scale": 4.0}],
    "light": [
        {"type": "sun", "direction": [0.6, -0.7, -0.4], "irradiance": 1476.0,
         "temperature": 5800.0},
        {"type": "distant", "direction": [0.2, -0.1, -1.0], "irradiance": 300.0,
         "color": [0.6, 0.75, 1.0]},
    ],
    "output": {"path": "out.exr"},
}

FOG_TOML = """[film]
resolution = [24, 24]
spp = 4
seed = 1

[render]
integrator = "volpath"

[camera]
position = [0.0, 1.0, 3.2]
look_at = [0.0, 1.0, 0.0]
fov = 40.0

[[volume]]
file = "fog_sphere.vdb"
shader = "smoke"
density_scale = 4.0

[[light]]
type = "sun"
direction = [0.6, -0.7, -0.4]
irradiance = 1476.0
temperature = 5800.0

[[light]]
type = "distant"
direction = [0.2, -0.1, -1.0]
irradiance = 300.0
color = [0.6, 0.75, 1.0]

[output]
path = "out.exr"
"""


def run_mirage(*args, cwd=None):
    """The mirage command; its CompletedProcess (text)."""
    return subprocess.run([MIRAGE, *args], cwd=cwd, capture_output=True, text=True)


@pytest.fixture(scope="session")
def fog_dir(tmp_path_factory):
    """A folder with fog_sphere.vdb (32 voxels over 2 m) and shot.toml, the scene above."""
    d = tmp_path_factory.mktemp("fog")
    r = run_mirage("make-asset", "fog-sphere", "-o", str(d / "fog_sphere.vdb"),
                   "--resolution", "32")
    assert r.returncode == 0, r.stderr
    (d / "shot.toml").write_text(FOG_TOML)
    return d


@pytest.fixture(scope="session")
def fog_scene_path(fog_dir):
    return str(fog_dir / "shot.toml")


def resident_bytes():
    """This process's resident set (Linux)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
