#!/usr/bin/env python3
"""Beam against point estimate at equal error, from a `mirage tradeoff` CSV.

The CSV must vary `estimate` (beam, point) and one cost knob (photons or k). For each estimate
the measured points, ordered by time, form a polyline of log(relMSE) against log(seconds); the
target error is the largest relMSE that both polylines reach at their slowest setting
(max of the two minima), so neither curve is extrapolated. Each estimate's time at the target is
read off its polyline by linear interpolation in log-log space (error falls as a power of the
cost, so the log-log curve is nearly straight between measured points).

Usage: equal_error.py tradeoff.csv   → prints the target relMSE, both times and their ratio.
"""
import csv
import math
import sys


def curve(rows, estimate):
    pts = sorted((float(r["seconds"]), float(r["relmse"])) for r in rows
                 if r["estimate"] == estimate)
    if len(pts) < 2:
        sys.exit(f"equal_error: fewer than 2 '{estimate}' rows in the CSV")
    return pts


def time_at(pts, target):
    """Seconds at which the polyline first reaches relMSE ≤ target (log-log interpolation)."""
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 > target >= e1:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return next(t for t, e in pts if e <= target)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: equal_error.py tradeoff.csv")
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "estimate" not in rows[0]:
        sys.exit(f"equal_error: {sys.argv[1]}: expected a column 'estimate' (--vary estimate=beam,point)")
    beam, point = curve(rows, "beam"), curve(rows, "point")
    target = max(min(e for _, e in beam), min(e for _, e in point))
    tb, tp = time_at(beam, target), time_at(point, target)
    print(f"  equal relMSE {target:.4g}: beam {tb:.2f} s, point {tp:.2f} s, "
          f"ratio point / beam {tp / tb:.2f}")


if __name__ == "__main__":
    main()
