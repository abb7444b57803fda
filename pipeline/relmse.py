#!/usr/bin/env python3
"""relMSE of an image against a reference over the reference's covered pixels.

relMSE = mean over pixels whose reference alpha > 0.01 and over R, G, B of
(x − r)² / (r² + ε), ε = 1e-3 · (mean of r over those pixels)². The images are read through
oiiotool --dumpdata, so no Python imaging package is needed.

Usage: relmse.py image.exr reference.exr   → prints the relMSE.
"""
import subprocess
import sys


def read_rgba(exr):
    """Pixels of an RGBA EXR as [(r, g, b, a)], from oiiotool --dumpdata."""
    text = subprocess.run(["oiiotool", "--dumpdata", exr], check=True, capture_output=True,
                          text=True).stdout
    pixels = []
    for line in text.splitlines():
        if "Pixel (" in line:
            values = [float(v) for v in line.split(":", 1)[1].split()]
            if len(values) < 4:
                sys.exit(f"relmse: {exr}: expected RGBA pixels")
            pixels.append(values[:4])
    return pixels


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: relmse.py image.exr reference.exr")
    x, r = read_rgba(sys.argv[1]), read_rgba(sys.argv[2])
    if len(x) != len(r):
        sys.exit("relmse: the images differ in size")
    covered = [i for i, p in enumerate(r) if p[3] > 0.01]
    if not covered:
        sys.exit("relmse: no pixel of the reference has alpha > 0.01")
    mean = sum(r[i][c] for i in covered for c in range(3)) / (3 * len(covered))
    eps = 1e-3 * mean * mean
    total = 0.0
    for i in covered:
        for c in range(3):
            ref = r[i][c]
            total += (x[i][c] - ref) ** 2 / (ref * ref + eps)
    print(f"{total / (3 * len(covered)):.6g}")


if __name__ == "__main__":
    main()
