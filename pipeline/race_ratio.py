#!/usr/bin/env python3
"""Equal-error time ratios of a race (pipeline/race.sh).

Reads a CSV with columns renderer, spp, seconds, relmse (one row per render, one renderer named
`cycles`). For every Cycles row, each other renderer's time to reach that relMSE is read off
its polyline of log(relMSE) against log(seconds) (pipeline/equal_error.py's interpolation).
Outside a renderer's measured range:
- an error below its best render's is extrapolated from its last two points, marked ~;
- an error above its worst render's (its cheapest render is already better than that) is
  given as a bound, ≤ that render's time, which is what a user can get; the straight-line
  extrapolation to a cheaper render that does not exist follows it, marked ~.

Usage: race_ratio.py race.csv   → one line per Cycles row and renderer.
       race_ratio.py --self-test → checks the three cases on a made-up race.
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


def curves_of(rows):
    """{renderer: [(seconds, relmse)] sorted by time} of a race's CSV rows."""
    curves = {}
    for r in rows:
        curves.setdefault(r["renderer"], []).append((float(r["seconds"]), float(r["relmse"])))
    return {name: sorted(pts) for name, pts in curves.items()}


def time_to(pts, ec):
    """A renderer's time to relMSE ec: (seconds, mark), mark "" (read off its curve), "~"
    (extrapolated below its best error) or "<=" (its cheapest render, already below ec);
    (None, "") from a single measurement outside it."""
    lo, hi = min(e for _, e in pts), max(e for _, e in pts)
    if lo <= ec <= hi:
        return time_at(pts, ec), ""
    if len(pts) < 2:
        return None, ""
    if ec > hi:
        return min(pts)[0], "<="
    return extrapolate(pts, ec), "~"


def ratio_lines(rows):
    curves = curves_of(rows)
    cycles = curves.pop("cycles", [])
    lines = []
    for tc, ec in cycles:
        for name, pts in sorted(curves.items()):
            head = f"  at Cycles' relMSE {ec:.4g} ({tc:.2f} s): {name}"
            t, mark = time_to(pts, ec)
            if mark == "":
                if t is None:
                    lines.append(f"{head}: one measurement, no curve to read it off")
                else:
                    lines.append(f"{head} {t:.2f} s, ratio {name} / cycles {t / tc:.2f}")
            elif mark == "<=":
                err = min(pts)[1]
                x = extrapolate(pts, ec)
                lines.append(f"{head} <={t:.2f} s (its cheapest render, relMSE {err:.4g}, "
                             f"is already below), ratio {name} / cycles <={t / tc:.2f}; "
                             f"extrapolated ~{x:.2f} s, ~{x / tc:.2f}")
            else:
                lines.append(f"{head} ~{t:.2f} s, ratio {name} / cycles ~{t / tc:.2f}")
    return lines


def self_test():
    rows = [{"renderer": n, "seconds": str(t), "relmse": str(e)} for n, t, e in [
        ("cycles", 1.0, 1.0), ("cycles", 4.0, 0.25), ("cycles", 16.0, 0.0625),
        ("mirage", 0.5, 0.5), ("mirage", 2.0, 0.125)]]
    lines = ratio_lines(rows)
    assert len(lines) == 3, lines
    # Above Mirage's worst error: its cheapest render bounds the time.
    assert "<=0.50 s" in lines[0] and "<=0.50;" in lines[0] and "~0.25 s" in lines[0], lines[0]
    # Inside: log-log interpolation (error ∝ 1/t here, so 0.25 at 1 s).
    assert lines[1].endswith("mirage 1.00 s, ratio mirage / cycles 0.25"), lines[1]
    # Below its best error: extrapolated, marked ~.
    assert lines[2].endswith("~4.00 s, ratio mirage / cycles ~0.25"), lines[2]
    print("race_ratio self-test: ok")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    if len(sys.argv) != 2:
        sys.exit("usage: race_ratio.py race.csv | --self-test")
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    for line in ratio_lines(rows):
        print(line)


if __name__ == "__main__":
    main()
