#!/usr/bin/env python3
"""The plot of a race (pipeline/race.sh): relMSE against time, both on log scales, one polyline
per renderer of its CSV (columns renderer, spp, seconds, relmse), each point a render.

Equal error is a horizontal line across the plot: the renderer whose curve crosses it further
left reaches that error sooner, and the horizontal distance between two curves is the log of
their time ratio (what pipeline/race_ratio.py reads off).

The picture is drawn here into an RGB raster and written as a PNG with zlib (no Python package
beyond the standard library); the text (title, axes' numbers, legend) is drawn by oiiotool
--text on a canvas of its own (fonts-dejavu-core, as pipeline/gallery.sh) and subtracted from
the white plot, which leaves black text. Without oiiotool or a font the plot has no text.

Usage: race_plot.py race.csv out.png [TITLE]
       race_plot.py --self-test
"""
import csv
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

WIDTH, HEIGHT = 760, 520
LEFT, RIGHT, TOP, BOTTOM = 70, 200, 40, 50  # margins: axes' numbers left and below, legend right
FONT = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
# Series colours: Cycles black; Mirage's default blue (given samples) and light blue (given a
# time); its named integrators and samplers in colours of their own.
COLOURS = {"cycles": (0, 0, 0), "mirage default": (31, 90, 200), "mirage timed": (90, 170, 240),
           "mirage volpath": (230, 120, 20), "mirage sobol": (230, 120, 20),
           "mirage random": (150, 90, 40), "mirage single": (40, 160, 60),
           "mirage photon": (150, 60, 170)}
OTHER = [(200, 40, 40), (120, 120, 120), (0, 150, 150)]


class Canvas:
    def __init__(self, w, h):
        self.w, self.h = w, h
        self.px = bytearray([255] * (3 * w * h))

    def dot(self, x, y, rgb):
        if 0 <= x < self.w and 0 <= y < self.h:
            i = 3 * (y * self.w + x)
            self.px[i:i + 3] = bytes(rgb)

    def line(self, x0, y0, x1, y1, rgb, width=1, dash=0):
        n = max(abs(x1 - x0), abs(y1 - y0), 1)
        for k in range(n + 1):
            if dash and (k // dash) % 2:
                continue
            x, y = round(x0 + (x1 - x0) * k / n), round(y0 + (y1 - y0) * k / n)
            for d in range(width):
                self.dot(x + (d if abs(y1 - y0) > abs(x1 - x0) else 0),
                         y + (d if abs(y1 - y0) <= abs(x1 - x0) else 0), rgb)

    def box(self, x, y, r, rgb):
        for dy in range(-r, r + 1):
            for dx in range(-r, r + 1):
                self.dot(x + dx, y + dy, rgb)

    def png(self):
        raw = b"".join(b"\0" + bytes(self.px[3 * y * self.w:3 * (y + 1) * self.w])
                       for y in range(self.h))

        def chunk(kind, data):
            return (struct.pack(">I", len(data)) + kind + data +
                    struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
        return (b"\x89PNG\r\n\x1a\n" +
                chunk(b"IHDR", struct.pack(">IIBBBBB", self.w, self.h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def read_series(path):
    series = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            t, e = float(r["seconds"]), float(r["relmse"])
            if t > 0 and e > 0:
                series.setdefault(r["renderer"], []).append((t, e))
    return {name: sorted(pts) for name, pts in series.items()}


def decades(lo, hi):
    """Powers of ten covering [lo, hi], one decade of margin where the data end on one."""
    a, b = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
    return a, b if b > a else a + 1


def number(k):
    """10^k as a plain number: 0.001 … 1000, else 1e-5."""
    return f"{10.0 ** k:g}" if -3 <= k <= 3 else f"1e{k}"


def draw(series, title):
    """The raster and the text labels [(x, y, size, text)] of the plot."""
    c = Canvas(WIDTH, HEIGHT)
    ts = [t for pts in series.values() for t, _ in pts]
    es = [e for pts in series.values() for _, e in pts]
    (x0, x1), (y0, y1) = decades(min(ts), max(ts)), decades(min(es), max(es))
    pw, ph = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM

    def at(t, e):
        return (round(LEFT + pw * (math.log10(t) - x0) / (x1 - x0)),
                round(TOP + ph * (y1 - math.log10(e)) / (y1 - y0)))

    labels = [(LEFT, 24, 15, title)]
    for k in range(x0, x1 + 1):
        x = at(10.0 ** k, 10.0 ** y0)[0]
        c.line(x, TOP, x, TOP + ph, (220, 220, 220))
        labels.append((x - 12, TOP + ph + 18, 12, number(k)))
    for k in range(y0, y1 + 1):
        y = at(10.0 ** x0, 10.0 ** k)[1]
        c.line(LEFT, y, LEFT + pw, y, (220, 220, 220))
        labels.append((LEFT - 48, y + 4, 12, number(k)))
    c.line(LEFT, TOP, LEFT, TOP + ph, (0, 0, 0))
    c.line(LEFT, TOP + ph, LEFT + pw, TOP + ph, (0, 0, 0))
    labels.append((LEFT + pw // 2 - 60, HEIGHT - 10, 13, "seconds (2 threads)"))
    labels.append((8, TOP - 8, 13, "relMSE"))
    others = iter(OTHER)
    for i, (name, pts) in enumerate(sorted(series.items(), key=lambda s: s[0] != "cycles")):
        rgb = COLOURS.get(name) or next(others, (0, 0, 0))
        dash = 4 if name == "mirage timed" else 0
        xy = [at(t, e) for t, e in pts]
        for (a, b), (p, q) in zip(xy, xy[1:]):
            c.line(a, b, p, q, rgb, 2, dash)
        for a, b in xy:
            c.box(a, b, 3, rgb)
        ly = TOP + 10 + 22 * i
        c.line(WIDTH - RIGHT + 14, ly, WIDTH - RIGHT + 40, ly, rgb, 2, dash)
        c.box(WIDTH - RIGHT + 27, ly, 3, rgb)
        labels.append((WIDTH - RIGHT + 46, ly + 5, 12, name))
    return c, labels


def write(canvas, labels, out):
    """The PNG with its text, or without it when oiiotool cannot draw text here."""
    with tempfile.TemporaryDirectory() as tmp:
        plain = os.path.join(tmp, "plain.png")
        with open(plain, "wb") as f:
            f.write(canvas.png())
        if shutil.which("oiiotool") and os.path.isfile(FONT):
            cmd = ["oiiotool", plain, "--create", f"{WIDTH}x{HEIGHT}", "3"]
            for x, y, size, text in labels:
                cmd += [f"--text:x={x}:y={y}:size={size}:color=1,1,1:font={FONT}", text]
            cmd += ["--sub", "-o", out]
            if subprocess.run(cmd, capture_output=True).returncode == 0:
                return
        print("race_plot: no text (oiiotool or its font missing)", file=sys.stderr)
        shutil.copyfile(plain, out)


def self_test():
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "race.csv")
        with open(path, "w") as f:
            f.write("renderer,spp,seconds,relmse\ncycles,4,1.0,1.0\ncycles,16,4.0,0.25\n"
                    "mirage default,4,0.5,0.5\nmirage default,16,2.0,0.12\n")
        series = read_series(path)
        canvas, labels = draw(series, "test")
        # Both curves are drawn in their colours, on axes of whole decades.
        assert canvas.px.count(bytes(COLOURS["mirage default"])) > 50
        assert canvas.px.count(bytes(COLOURS["cycles"])) > 50
        assert decades(0.5, 4.0) == (-1, 1) and decades(0.12, 1.0) == (-1, 0)
        assert number(-2) == "0.01" and number(5) == "1e5"
        assert any(t == "mirage default" for *_, t in labels)
        out = os.path.join(tmp, "plot.png")
        write(canvas, labels, out)
        with open(out, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    print("race_plot self-test: ok")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: race_plot.py race.csv out.png [TITLE] | --self-test")
    series = read_series(sys.argv[1])
    if not series:
        sys.exit(f"race_plot: {sys.argv[1]}: no rows")
    title = sys.argv[3] if len(sys.argv) == 4 else os.path.basename(sys.argv[1])
    write(*draw(series, title + ": relMSE against seconds"), sys.argv[2])


if __name__ == "__main__":
    main()
