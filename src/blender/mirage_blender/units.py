"""Blender's conventions in Mirage's: axes, and the units of lights (docs/blender.md, "Units").

Pure Python, no bpy: the numbers below are the whole of the conversion, and the tests read them.

Axes. Blender's world is right-handed with +Z up; Mirage's is right-handed with +Y up (its
camera's default up, its dome's zenith). A Blender point (x, y, z) is Mirage's (x, z, -y): the
rotation by -90 degrees about +X, which keeps handedness, so no image is mirrored.

Light units. Both renderers are judged by what the camera sees of a white Lambertian plane lit
by the light (its radiance, as RGB in the working space: linear Rec.709, the add-on's OCIO
config). Cycles gives a light of colour c and strength P an RGB radiant flux P·c (sun: an RGB
irradiance S·c); Mirage gives a light of power Φ (irradiance E) a spectrum normalised to total
Φ over 360-830 nm whose shape has exactly the RGB of c, so its RGB flux is Φ·c / I(c), I(c) the
integral over 360-830 nm of the spectrum Mirage builds for c at unit RGB. I is linear in c
where the spectrum needs no clipping (every colour of a real lamp):
I(c) = 219.067 r + 71.220 g + 152.350 b watts, measured by rendering a white plane under a sun
of each colour with Mirage's volpath integrator, 8x8 pixels, 256 samples (docs/blender.md gives
the scene; residuals below 1e-5 of I over six colours; I(white) = 442.64, the factor of
tests/bench/smoke1_cycles.toml in the ACEScg working space as well).
"""
import math

# I(c) = dot(ILLUMINANT_WATTS, c), W per unit of RGB flux (module docstring).
ILLUMINANT_WATTS = (219.067, 71.220, 152.350)

# Cycles 3.4's point and spot lights of P watts radiate P / (4 pi) W/sr (a sphere light of
# radius r and radiance P / (4 pi * pi r^2), seen from afar); Mirage's point light of Phi watts
# radiates Phi / (4 pi): the same law. Cycles' area light of P watts has radiance P / (4 A),
# a Lambertian emitter whose flux is pi * A * L = (pi / 4) P; Mirage's quad of Phi watts has
# radiance Phi / (pi A).
AREA_FLUX_PER_WATT = math.pi / 4.0


# The same rotation as a matrix (rows: Mirage's x, y, z in Blender's axes); a mathutils Matrix
# where Blender runs this module, a tuple of rows elsewhere.
_AXES_ROWS = ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0.0, -1.0, 0.0))
try:
    from mathutils import Matrix
    AXES = Matrix(_AXES_ROWS)
except ImportError:
    AXES = _AXES_ROWS


def to_mirage(v):
    """A Blender world vector or point, as Mirage's (x, z, -y)."""
    return [float(v[0]), float(v[2]), -float(v[1])]


def illuminant_integral(color):
    """I(c): Mirage's watts per unit of RGB flux for a light of colour c (module docstring)."""
    return sum(w * max(float(x), 0.0) for w, x in zip(ILLUMINANT_WATTS, color))


def sun_irradiance(strength, color):
    """Mirage's irradiance (W/m^2) for Cycles' sun of `strength` W/m^2 and colour c."""
    return strength * illuminant_integral(color)


def point_power(watts, color):
    """Mirage's point-light power for Cycles' point light of `watts` and colour c."""
    return watts * illuminant_integral(color)


def spot_power(watts, color, cos_inner, cos_outer):
    """Mirage's spot power for Cycles' spot of `watts`, colour c, on-axis intensity equal.

    Cycles' spot is its point light masked by the cone: P / (4 pi) W/sr on the axis. Mirage's
    spot spreads Phi over the solid angle 2 pi (1 - (cos_inner + cos_outer) / 2) of its cone
    (its smoothstep ramp counted at half), src/light/lights.cpp.
    """
    omega = 2.0 * math.pi * (1.0 - 0.5 * (cos_inner + cos_outer))
    return watts / (4.0 * math.pi) * omega * illuminant_integral(color)


def area_power(watts, color):
    """Mirage's quad power for Cycles' area light of `watts` and colour c (same radiance)."""
    return watts * AREA_FLUX_PER_WATT * illuminant_integral(color)


def spot_cone(spot_size, spot_blend):
    """Mirage's (cone_angle, cone_inner) in degrees for Blender's spot size (the full angle,
    radians) and blend: Cycles ramps its spot by a smoothstep over cos theta from cos(size/2)
    to cos(size/2) + (1 - cos(size/2)) * blend, Mirage by a smoothstep from cos(cone_angle) to
    cos(cone_inner)."""
    half = 0.5 * spot_size
    cos_inner = min(1.0, math.cos(half) + (1.0 - math.cos(half)) * spot_blend)
    return math.degrees(half), math.degrees(math.acos(cos_inner))


def dome_rotation(mapping_z_radians):
    """Mirage's dome `rotation` (degrees about +y) for Blender's equirectangular world seen
    through a Mapping node turning the lookup vector by `mapping_z_radians` about +Z.

    Blender's image centre looks along -X with +Y to its right; Mirage's along -z with +x to its
    right. In Mirage's axes Blender's -X is -x and +Y is -z: Mirage's dome turned by 90 degrees
    about +y. A Mapping rotation phi turns the lookup vector, so the image turns by -phi.
    """
    deg = 90.0 - math.degrees(mapping_z_radians)
    return (deg + 180.0) % 360.0 - 180.0
