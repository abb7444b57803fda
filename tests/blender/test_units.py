"""The add-on's conversions that need no Blender (src/blender/mirage_blender/units.py and
toml_text.py): axes, light units and cones against their definitions, TOML written and read."""
import math
import os
import sys
import tomllib

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "src", "blender",
                                "mirage_blender"))
import toml_text  # noqa: E402
import units  # noqa: E402


def test_z_up_becomes_y_up_and_keeps_handedness():
    assert units.to_mirage((0, 0, 1)) == [0, 1, 0]        # Blender's up is Mirage's up
    assert units.to_mirage((0, 1, 0)) == [0, 0, -1]       # Blender's forward (+Y) is Mirage's -z
    x, y, z = (units.to_mirage(v) for v in ((1, 0, 0), (0, 1, 0), (0, 0, 1)))
    cross = [x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]]
    assert cross == z                                      # a rotation, not a mirror


def test_light_units_are_linear_in_colour_and_power():
    white = units.illuminant_integral((1, 1, 1))
    assert white == pytest.approx(442.637, abs=1e-3)     # units.py: the measured I(white)
    assert units.sun_irradiance(2.0, (1, 1, 1)) == pytest.approx(2 * white)
    assert units.point_power(10.0, (1, 0.5, 0.2)) == pytest.approx(
        10 * (219.067 + 0.5 * 71.220 + 0.2 * 152.350))
    assert units.area_power(4.0, (1, 1, 1)) == pytest.approx(math.pi * white)


def test_spot_keeps_the_on_axis_intensity_of_cycles():
    outer, inner = units.spot_cone(math.radians(60.0), 0.25)
    assert outer == pytest.approx(30.0)
    cos_o = math.cos(math.radians(30.0))
    assert math.cos(math.radians(inner)) == pytest.approx(cos_o + (1 - cos_o) * 0.25)
    phi = units.spot_power(100.0, (1, 1, 1), math.cos(math.radians(inner)), cos_o)
    omega = 2 * math.pi * (1 - 0.5 * (math.cos(math.radians(inner)) + cos_o))
    # Mirage's on-axis intensity Φ/Ω (per unit of RGB flux) is Cycles' P / 4π.
    assert phi / omega / units.illuminant_integral((1, 1, 1)) == pytest.approx(100 / (4 * math.pi))


def test_dome_rotation_puts_blenders_image_centre_on_minus_x():
    assert units.dome_rotation(0.0) == pytest.approx(90.0)
    assert units.dome_rotation(math.radians(90.0)) == pytest.approx(0.0)
    assert units.dome_rotation(math.radians(-120.0)) == pytest.approx(-150.0)


def test_toml_round_trip():
    doc = {"film": {"resolution": [64, 48], "spp": 8}, "render": {"integrator": "single"},
           "volume": [{"file": "a \"b\".vdb", "bind": {"density": "d"}, "density_scale": 0.25,
                       "transform": {"rotate": [30.0, 0.0, 1.0, 0.0]}}],
           "light": [{"type": "sun", "color": [1.0, 0.5, 0.25]}, {"type": "dome"}],
           "output": {"half": False}, "name": "top"}
    assert tomllib.loads(toml_text.dumps(doc)) == doc
