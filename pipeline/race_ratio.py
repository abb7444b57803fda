#!/usr/bin/env python3
"""Equal-error time ratios of a race (pipeline/race.sh).

Reads a CSV with columns renderer, spp, seconds, relmse (one row per render, one renderer named
`cycles`). For every Cycles row, each other renderer's time to reach that relMSE is read off
its polyline of log(relMSE) against log(seconds) (pipeline/equal_error.py's interpolation; a
target beyond a renderer's measured range is extrapolated from its last two points, marked ~).

Usage: race_ratio.py race.csv   → one line per Cycles row and renderer.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from equal_error import time_at  # noqa: E402


def extrapolate(pts, target):
    (t0, e0), (t1, e1) = (pts[0], pts[1]) if target > pts[0][1] else (pts[-2], pts[-1])
    slope = (math.log(t1) - math.log(t0)) / (math.log(e1) - math.log(e0))
    return math.exp(math.log(t0) + slope * (math.log(target) - math.log(e0)))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: race_ratio.py race.csv")
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    curves = {}
    for r in rows:
        curves.setdefault(r["renderer"], []).append((float(r["seconds"]), float(r["relmse"])))
    cycles = sorted(curves.pop("cycles", []))
    for tc, ec in cycles:
        for name, pts in sorted(curves.items()):
            pts = sorted(pts)
            inside = min(e for _, e in pts) <= ec <= max(e for _, e in pts)
            if not inside and len(pts) < 2:
                print(f"  at Cycles' relMSE {ec:.4g}: {name}: one measurement, no curve to read it off")
                continue
            t = time_at(pts, ec) if inside else extrapolate(pts, ec)
            print(f"  at Cycles' relMSE {ec:.4g} ({tc:.2f} s): {name} {'' if inside else '~'}"
                  f"{t:.2f} s, ratio {name} / cycles {'' if inside else '~'}{t / tc:.2f}")


if __name__ == "__main__":
    main()
