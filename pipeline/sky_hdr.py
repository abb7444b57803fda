#!/usr/bin/env python3
"""The sky of the regime suite's `sky-hdr` race: a lat-long Radiance .hdr with a small sun.

One radiance function of direction, written twice, once in each renderer's lat-long convention,
so that Mirage and Cycles are lit by the same sky (pipeline/race.sh sky-hdr; docs/regimes.md).
Directions are in the scene's frame, the VDB's own (y up; the race camera looks along -z).

The sky (linear Rec.709 radiance, W·m⁻²·sr⁻¹ in the units both renderers read an image in):
- above the horizon, a gradient from a pale horizon (0.85, 0.90, 1.00) to a blue zenith
  (0.25, 0.45, 1.00), mixed by w = sqrt(sin e) (e the elevation), so most of the dome is
  the blue of its upper part and only the last ~10° pale; times SKY (0.5);
- below it, a dark ground of (0.12, 0.11, 0.10) × SKY, a grey ground seen from above;
- the sun, a disc of angular radius SUN_RADIUS_DEG (1.5°, six times the real sun's 0.27°, so
  that an 8-pixel-wide disc of the 1024×512 map holds it rather than one pixel), of warm white
  (1.00, 0.95, 0.85) and luminance SUN_TO_ZENITH (15 000) times the zenith's, in the direction
  SUN_DIR (towards the sun: elevation 35°, from the camera's upper left and in front of the
  cloud). Its irradiance on a plane facing it, L·Ω with Ω = 2π(1 − cos 1.5°) = 2.15·10⁻³ sr, is
  about 8 times the sky's on a horizontal plane: a clear day's ratio of direct to diffuse light.
Each pixel holds the sky at its centre's direction (the sun's edge is a pixel's step).

Conventions (pixel (i, j) of a W×H image, row j = 0 at the top, centre u = (i + ½)/W,
v = (j + ½)/H):
- mirage: θ = πv from +y (the top row is the zenith), φ = 2πu, d = (−sin θ sin φ, cos θ,
  sin θ cos φ): the centre column looks along −z, +x at u = ¾ (docs/scene-file.md, "Lights";
  src/light/dome_light.cpp). Mirage reads a map's pixels in its working space, ACEScg, so the
  Rec.709 values are converted by the Bradford-adapted Rec.709 → ACEScg matrix of Mirage's
  built-in OCIO config (assets/ocio/config.ocio: Rec.709 red → (0.613097, 0.070194, 0.020616)).
- cycles: Blender's equirectangular environment (Cycles' direction_to_equirectangular) with
  Blender's own up axis, +z, since cycles_vdb.py puts the VDB's frame in Blender's unchanged:
  the top row is +z (towards the race camera), u = ½ − atan2(d.y, d.x)/2π. Values stay
  linear Rec.709, Blender's scene-linear space.

The file is an uncompressed (flat) Radiance RGBE image, which OpenImageIO and Blender read.

Usage: sky_hdr.py {mirage | cycles} out.hdr [WIDTH]   (WIDTH 1024; height WIDTH/2)
       sky_hdr.py --self-test
"""
import math
import sys

SKY = 0.5
ZENITH = (0.25, 0.45, 1.00)
HORIZON = (0.85, 0.90, 1.00)
GROUND = (0.12, 0.11, 0.10)
SUN_COLOUR = (1.00, 0.95, 0.85)
SUN_RADIUS_DEG = 1.5
SUN_TO_ZENITH = 15000.0
SUN_ELEVATION_DEG = 35.0
SUN_AZIMUTH_DEG = 40.0  # from +z (towards the camera) towards −x (the camera's left)

# Linear Rec.709 (D65) → ACEScg (AP1, ACES white), Bradford-adapted, as Mirage's built-in config.
REC709_TO_ACESCG = ((0.6130974, 0.3395231, 0.0473795),
                    (0.0701937, 0.9163539, 0.0134524),
                    (0.0206156, 0.1095698, 0.8698151))


def luminance(rgb):
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]


def sun_direction():
    e, a = math.radians(SUN_ELEVATION_DEG), math.radians(SUN_AZIMUTH_DEG)
    return (-math.cos(e) * math.sin(a), math.sin(e), math.cos(e) * math.cos(a))


SUN_DIR = sun_direction()
COS_SUN_RADIUS = math.cos(math.radians(SUN_RADIUS_DEG))
SUN = tuple(SUN_TO_ZENITH * luminance(ZENITH) * SKY / luminance(SUN_COLOUR) * c for c in SUN_COLOUR)


def sky(d):
    """Linear Rec.709 radiance arriving from direction d (unit, pointing at the sky)."""
    if d[0] * SUN_DIR[0] + d[1] * SUN_DIR[1] + d[2] * SUN_DIR[2] >= COS_SUN_RADIUS:
        return SUN
    if d[1] < 0.0:
        return tuple(SKY * c for c in GROUND)
    w = math.sqrt(d[1])
    return tuple(SKY * (h + w * (z - h)) for h, z in zip(HORIZON, ZENITH))


def direction(convention, u, v):
    if convention == "mirage":
        theta, phi = math.pi * v, 2.0 * math.pi * u
        return (-math.sin(theta) * math.sin(phi), math.cos(theta),
                math.sin(theta) * math.cos(phi))
    # Cycles: u = ½ − atan2(d.y, d.x)/2π, v_blender = 1 − acos(d.z)/π, with v_blender measured
    # from the bottom row, so the top row (v = 0 here) is d.z = 1.
    theta, phi = math.pi * v, math.pi * (1.0 - 2.0 * u)
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))


def pixel_value(convention, rgb):
    if convention == "mirage":
        return tuple(sum(m * c for m, c in zip(row, rgb)) for row in REC709_TO_ACESCG)
    return rgb


def rgbe(rgb):
    m = max(rgb)
    if m < 1e-32:
        return b"\0\0\0\0"
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([int(c * scale) for c in rgb] + [exponent + 128])


def image(convention, width):
    height = width // 2
    rows = []
    for j in range(height):
        row = bytearray()
        for i in range(width):
            d = direction(convention, (i + 0.5) / width, (j + 0.5) / height)
            row += rgbe(pixel_value(convention, sky(d)))
        rows.append(bytes(row))
    return width, height, rows


def write_hdr(path, width, height, rows):
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {height} +X {width}\n".encode())
        for row in rows:
            f.write(row)


def self_test():
    # The two conventions agree on where the sun is: the brightest pixel of each image maps to
    # the sun's direction.
    for convention in ("mirage", "cycles"):
        width, height, rows = image(convention, 256)
        best = max(((r[4 * i + 3], i, j) for j, r in enumerate(rows) for i in range(width)))
        d = direction(convention, (best[1] + 0.5) / width, (best[2] + 0.5) / height)
        cos = sum(a * b for a, b in zip(d, sun_direction()))
        assert cos > math.cos(math.radians(2 * SUN_RADIUS_DEG)), (convention, d)
    # Mirage's convention as documented: the centre column looks along −z, u = ¾ is +x, the top
    # row is +y; Cycles': the centre column is +x, u = ¼ is +y, the top row +z.
    for conv, u, v, want in (("mirage", 0.5, 0.5, (0, 0, -1)), ("mirage", 0.75, 0.5, (1, 0, 0)),
                             ("mirage", 0.3, 0.0, (0, 1, 0)), ("cycles", 0.5, 0.5, (1, 0, 0)),
                             ("cycles", 0.25, 0.5, (0, 1, 0)), ("cycles", 0.3, 0.0, (0, 0, 1))):
        got = direction(conv, u, v)
        assert all(abs(a - b) < 1e-9 for a, b in zip(got, want)), (conv, u, v, got)
    # RGBE round trip within its 8-bit mantissa; Rec.709 white stays white in ACEScg.
    r, g, b, e = rgbe((3.0, 1.5, 0.25))
    back = [c * 2.0 ** (e - 136) for c in (r, g, b)]
    assert all(abs(x - y) <= y / 128 + 2.0 ** (e - 136) for x, y in zip(back, (3.0, 1.5, 0.25)))
    assert all(abs(c - 1.0) < 1e-6 for c in pixel_value("mirage", (1.0, 1.0, 1.0)))
    # The sun's irradiance over the sky's on a horizontal plane (documented as about 8).
    omega = 2 * math.pi * (1 - math.cos(math.radians(SUN_RADIUS_DEG)))
    sun = luminance(sky(sun_direction())) * omega
    n, sky_e = 200, 0.0
    for a in range(n):
        for b in range(4 * n):
            mu = (a + 0.5) / n
            phi = 2 * math.pi * (b + 0.5) / (4 * n)
            d = (math.sqrt(1 - mu * mu) * math.cos(phi), mu, math.sqrt(1 - mu * mu) * math.sin(phi))
            sky_e += luminance(sky(d)) * mu * (2 * math.pi / n / (4 * n)) if \
                sum(x * y for x, y in zip(d, sun_direction())) < 0.99 else 0.0
    assert 6 < sun / sky_e < 10, sun / sky_e
    print("sky_hdr self-test: ok")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    if len(sys.argv) not in (3, 4) or sys.argv[1] not in ("mirage", "cycles"):
        sys.exit("usage: sky_hdr.py {mirage | cycles} out.hdr [WIDTH] | --self-test")
    width = int(sys.argv[3]) if len(sys.argv) == 4 else 1024
    write_hdr(sys.argv[2], *image(sys.argv[1], width))


if __name__ == "__main__":
    main()
