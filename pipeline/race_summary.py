#!/usr/bin/env python3
"""The regime suite's table (pipeline/race.sh REGIME; docs/regimes.md).

For each regime raced into OUT (OUT/<regime>.csv), Mirage's default render's time over Cycles'
at Cycles' relMSE of 4, 16, 64 and 256 samples per pixel (pipeline/race_ratio.py's reading:
~ extrapolated below the default's best error, <= its cheapest render already below that
error), given samples (`--spp`, the rows "mirage default") and given a time (`--time-limit`,
"mirage timed"); then Cycles' own times and errors, the checks of a light inside a medium
(OUT/<regime>.checks.txt), the bounce checks (OUT/<regime>.bounces.txt) and when and where each
regime ran (OUT/<regime>.run.txt). Markdown, to paste.

Usage: race_summary.py OUT                  → the tables
       race_summary.py --mean image ref       → the image's mean R, G, B and luminance Y against
                                                the reference's, in per cent (race.sh's check)
       race_summary.py --exposure image       → the factor that brings the median luminance of
                                                the covered pixels (alpha > 0.01) that hold light
                                                to 0.18: previews exposed for the medium, where
                                                what is brighter (flames, a lamp) clips
       race_summary.py --self-test
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from race_ratio import curves_of, time_to  # noqa: E402
from relmse import read_rgba  # noqa: E402

REGIMES = ["sun", "sky-white", "sky-hdr", "lamp-point", "lamp-spot", "lamp-sphere", "fire",
           "haze"]
SPPS = [4, 16, 64, 256]
SERIES = [("mirage default", "given samples"), ("mirage timed", "given a time")]
ERRATIC = 1.5


def cycles_at(rows):
    """{spp: (seconds, relmse)} of the Cycles rows."""
    return {int(r["spp"]): (float(r["seconds"]), float(r["relmse"]))
            for r in rows if r["renderer"] == "cycles"}


def erratic(pts):
    """Whether a series' relMSE fails to fall as its time grows: a later render's error above
    ERRATIC times an earlier one's, which rare, heavy samples (fireflies) do, and a time limit's
    smooth coarse image followed by a noisier full pass; a time read off such a curve is not
    the curve's."""
    return any(b[1] > ERRATIC * a[1] for a, b in zip(pts, pts[1:]))


def cell(pts, tc, ec, flag):
    if not pts:
        return ""
    t, mark = time_to(pts, ec)
    if t is None:
        return ""
    return f"{flag}{mark.replace('<=', '≤')}{t / tc:.2f}"


def regime_rows(name, rows):
    curves, cyc = curves_of(rows), cycles_at(rows)
    out = []
    for series, label in SERIES:
        pts = curves.get(series)
        flag = "?" if pts and (erratic(pts) or erratic(curves.get("cycles", []))) else ""
        cells = [cell(pts, *cyc[s], flag) if s in cyc else "" for s in SPPS]
        out.append(f"| {name} | {label} | " + " | ".join(cells) + " |")
    return out


def check_row(name, text):
    """The checks of OUT/<regime>.checks.txt as a table row: the noise between two seeds of
    Mirage's default over Cycles' at equal samples, their mean seconds, the same noise ratio at
    equal time (a variance falls as 1/time), and the long render's mean luminance against the
    reference; "" when the file is not the checks' (an interrupted run)."""
    seeds = {}
    for who, a, b in re.findall(r"seeds (cycles|mirage default) .*\(([0-9.]+) s, ([0-9.]+) s\)",
                                text):
        seeds[who] = (float(a) + float(b)) / 2
    ratio = re.search(r"mirage / cycles ([0-9.]+)", text)
    mean = re.search(r"Y ([-+][0-9.]+ %)", text)
    if len(seeds) != 2 or not ratio or not mean:
        return ""
    r, tm, tc = float(ratio.group(1)), seeds["mirage default"], seeds["cycles"]
    return f"| {name} | {r:.2f} | {tm:.1f} / {tc:.1f} | {r * tm / tc:.2f} | {mean.group(1)} |"


def tables(out_dir):
    lines = ["Mirage's default render: its time over Cycles' at Cycles' relMSE of",
             "", "| regime | the default | 4 spp | 16 spp | 64 spp | 256 spp |",
             "|---|---|---:|---:|---:|---:|"]
    cycles_lines = ["", "Cycles (seconds / relMSE against its own converged image)", "",
                    "| regime | 4 spp | 16 spp | 64 spp | 256 spp |", "|---|---:|---:|---:|---:|"]
    checks = ["", "A light inside a medium: Mirage's default against Cycles (OUT/<regime>.checks.txt)",
              "", "| regime | noise between seeds, Mirage / Cycles at equal samples | seconds, "
              "Mirage / Cycles | noise at equal time | Mirage's long render's mean Y against "
              "its reference |", "|---|---:|---:|---:|---:|"]
    notes = []
    for name in REGIMES:
        path = os.path.join(out_dir, name + ".csv")
        if not os.path.isfile(path):
            continue
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        lines += regime_rows(name, rows)
        cyc = cycles_at(rows)
        cycles_lines.append(f"| {name} | " + " | ".join(
            f"{cyc[s][0]:.2f} / {cyc[s][1]:.3g}" if s in cyc else "" for s in SPPS) + " |")
        for kind in ("run", "bounces", "checks"):
            extra = os.path.join(out_dir, f"{name}.{kind}.txt")
            if os.path.isfile(extra):
                with open(extra) as f:
                    text = f.read()
                notes += [f"{name} {kind}: {line}" for line in text.splitlines() if line.strip()]
                if kind == "checks" and check_row(name, text):
                    checks.append(check_row(name, text))
    lines += ["", f"?: this series' or Cycles' relMSE does not fall with time (a later render's "
              f"above {ERRATIC}× an earlier one's: fireflies, or a short time limit's coarse image "
              "against a later full pass), so the ratio read off it is unreliable; where fireflies "
              "decide it, the checks below (noise between seeds, a long render's mean) measure it"]
    return lines + cycles_lines + (checks if len(checks) > 5 else []) + [""] + notes


def means(exr):
    """The mean R, G, B over the frame (oiiotool --stats)."""
    text = subprocess.run(["oiiotool", "--stats", exr], check=True, capture_output=True,
                          text=True).stdout
    for line in text.splitlines():
        if "Stats Avg:" in line:
            return [float(v) for v in line.split(":", 1)[1].split()[:3]]
    sys.exit(f"race_summary: {exr}: no statistics")


def luminance(rgb):
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]


def mean_line(image, reference):
    m, r = means(image), means(reference)
    m.append(luminance(m))
    r.append(luminance(r))
    return ", ".join(f"{c} {100.0 * (a / b - 1.0):+.1f} %" for c, a, b in zip("RGBY", m, r))


def exposure(image):
    ys = sorted(y for y in (luminance(p) for p in read_rgba(image) if p[3] > 0.01) if y > 0)
    median = ys[len(ys) // 2] if ys else 0.0
    return 0.18 / median if median > 0 else 1.0


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "fire.csv"), "w") as f:
            f.write("renderer,spp,seconds,relmse\ncycles,4,1.0,1.0\ncycles,16,4.0,0.25\n"
                    "cycles,64,16.0,0.0625\nmirage default,4,0.5,0.5\n"
                    "mirage default,16,2.0,0.125\nmirage timed,1,1.0,0.2\n")
        with open(os.path.join(tmp, "haze.csv"), "w") as f:
            f.write("renderer,spp,seconds,relmse\ncycles,16,4.0,10\ncycles,64,16.0,3\n"
                    "mirage timed,1,1.0,8\nmirage timed,3,3.0,40\nmirage timed,10,10.0,2\n")
        with open(os.path.join(tmp, "fire.checks.txt"), "w") as f:
            f.write("seeds cycles 64 spp: relMSE between seeds / 2 = 2 (10 s, 12 s)\n"
                    "seeds mirage default 64 spp: relMSE between seeds / 2 = 4 (1.5 s, 2.5 s); "
                    "mirage / cycles 2.00\nmean ... R +1.0 %, G +1.0 %, B +1.0 %, Y +1.0 %\n")
        text = "\n".join(tables(tmp))
    # Given samples: a bound at Cycles' 4-spp error, read off at 16, extrapolated at 64; given a
    # time: one render, a bound only where it is inside (none here: 0.2 is below 1.0 and above
    # 0.0625, and one measurement gives no curve).
    assert "| fire | given samples | ≤0.50 | 0.25 | ~0.25 |  |" in text, text
    assert "| fire | given a time |  |  |  |  |" in text, text
    assert "| fire | 1.00 / 1 | 4.00 / 0.25 | 16.00 / 0.0625 |  |" in text, text
    assert "fire checks: mean ... R +1.0 %, G +1.0 %, B +1.0 %, Y +1.0 %" in text, text
    # Twice Cycles' noise in 2 s against 11: at equal time 2 × 2 / 11.
    assert "| fire | 2.00 | 2.0 / 11.0 | 0.36 | +1.0 % |" in text, text
    # A timed series whose error rises from 1 s to 3 s: its cells are flagged as noise.
    assert "| haze | given a time |  | ?1.31 | ?0.53 |  |" in text, text
    print("race_summary self-test: ok")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
    elif len(sys.argv) == 4 and sys.argv[1] == "--mean":
        print(mean_line(sys.argv[2], sys.argv[3]))
    elif len(sys.argv) == 3 and sys.argv[1] == "--exposure":
        print(f"{exposure(sys.argv[2]):.6g}")
    elif len(sys.argv) == 2:
        print("\n".join(tables(sys.argv[1])))
    else:
        sys.exit("usage: race_summary.py OUT | --mean image.exr ref.exr | --exposure image.exr | "
                 "--self-test")


if __name__ == "__main__":
    main()
