#!/usr/bin/env python3
"""A regime scene of the suite (pipeline/race.sh check; docs/regimes.md) against its own
`# race.*` lines: what pipeline/race.sh would hand Cycles must describe the scene Mirage renders.

Each renderer is judged against its own converged image, so brightness need not match (Blender's
light watts are not Mirage's); what must is the picture: the medium and where the light is.
Checked, without running either renderer:
- the metadata: race.cache, race.cycles, race.bounces (an integer ≥ 0) and race.rows (volpath,
  single, photon) are given; race.checks holds only seeds and mean, race.times only positive
  seconds;
- every Cycles option is one ../shared/tools/cycles_vdb.py declares (a typo would otherwise
  surface as a Cycles error an hour into a run);
- the medium: Cycles' σt = --density-scale per unit density is Mirage's density_scale × (σa + σs)
  of the scene's one-component shader, its --albedo σs / (σa + σs), its --anisotropy the
  shader's g;
- the lights: Cycles' sun (--sun-strength > 0) along the Mirage sun's reversed direction
  (--sun-dir points at the sun, Mirage's direction is the light's travel); a point light at the
  same position (a Mirage sphere light's centre: cycles_vdb.py's lights have radius 0); a spot
  light at the same position and direction with Cycles' full cone angle twice Mirage's half
  angle; a white world (--world-color) where Mirage has a constant dome of
  that colour, an HDR world (--world-hdr sky.cycles.hdr) where its dome's map is the same sky in
  Mirage's convention (sky.mirage.hdr, pipeline/sky_hdr.py); no light Cycles has and Mirage not;
- fire: Cycles' --temperature-grid is the grid Mirage binds to the shader's temperature slot.

Usage: race_scene_check.py scene.toml cycles_vdb.py KEY=VALUES… -- CYCLES_ARGS…
       (KEY one of the metadata keys, VALUES its words; race.sh passes what it read)
       race_scene_check.py --self-test
Prints `<scene>: ok` or the first disagreement, and exits 1 on one.
"""
import math
import os
import re
import sys
import tempfile
import tomllib

ROWS = {"volpath", "single", "photon"}
CHECKS = {"seeds", "mean"}


def fail(scene, message):
    sys.exit(f"race_scene_check: {scene}: {message}")


def cycles_options(path):
    """{option: value} of Cycles' arguments, "--x=v" and "--x v" alike; a flag maps to ''."""
    opts, args = {}, list(path)
    while args:
        word = args.pop(0)
        if not word.startswith("--"):
            raise ValueError(f"'{word}' is not an option")
        if "=" in word:
            key, value = word.split("=", 1)
        else:
            key, value = word, args.pop(0) if args and not args[0].startswith("--") else ""
        opts[key] = value
    return opts


def known_options(cycles_vdb):
    with open(cycles_vdb) as f:
        return set(re.findall(r'add_argument\("(--[a-z-]+)"', f.read()))


def numbers(text):
    return [float(t) for t in text.split(",")]


def close(a, b, tol=1e-3):
    return all(abs(x - y) <= tol * max(1.0, abs(y)) for x, y in zip(a, b)) and len(a) == len(b)


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def check_metadata(scene, meta):
    for key in ("cache", "cycles", "bounces", "rows"):
        if not meta.get(key):
            fail(scene, f"no `# race.{key} = …` line")
    if not re.fullmatch(r"[0-9]+", meta["bounces"]):
        fail(scene, f"race.bounces '{meta['bounces']}' is not an integer")
    for key, allowed in (("rows", ROWS), ("checks", CHECKS)):
        unknown = set(meta.get(key, "").split()) - allowed
        if unknown:
            fail(scene, f"race.{key}: unknown {sorted(unknown)} (known: {sorted(allowed)})")
    for t in meta.get("times", "").split():
        if not re.fullmatch(r"[0-9.]+", t) or float(t) <= 0:
            fail(scene, f"race.times: '{t}' is not a positive number of seconds")


def check_medium(scene, doc, opts):
    vol = doc["volume"][0]
    with open(os.path.join(os.path.dirname(scene), vol["shader"]), "rb") as f:
        shader = tomllib.load(f)
    comps = shader.get("component", [])
    if len(comps) != 1:
        fail(scene, f"shader {vol['shader']}: Cycles' volume has one density, the shader "
                    f"{len(comps)} components")
    sa, ss = comps[0].get("sigma_a", 0.0), comps[0].get("sigma_s", 0.0)
    want = {"--density-scale": vol.get("density_scale", 1.0) * (sa + ss),
            "--albedo": ss / (sa + ss), "--anisotropy": comps[0].get("g", 0.0)}
    defaults = {"--density-scale": 5.0, "--albedo": 0.8, "--anisotropy": 0.0}
    for key, value in want.items():
        got = float(opts.get(key, defaults[key]))
        if not close([got], [value]):
            fail(scene, f"Cycles {key} {got}, Mirage's medium {value:.6g}")
    temperature = opts.get("--temperature-grid")
    bound = vol.get("bind", {}).get("temperature") if "emission" in shader else None
    if temperature != bound:
        fail(scene, f"Cycles --temperature-grid {temperature}, Mirage's temperature slot {bound}")


def check_sun(scene, lights, opts):
    suns = [l for l in lights if l["type"] in ("sun", "distant")]
    if float(opts.get("--sun-strength", 5.0)) == 0.0:
        if suns:
            fail(scene, "Mirage has a sun, Cycles none (--sun-strength 0)")
        return
    if len(suns) != 1:
        fail(scene, "Cycles has a sun (--sun-strength > 0), Mirage none")
    towards = unit([-x for x in suns[0]["direction"]])
    if not close(unit(numbers(opts.get("--sun-dir", "0.3,0.3,0"))), towards):
        fail(scene, f"Cycles' --sun-dir is not Mirage's sun reversed {towards}")


def check_lamps(scene, lights, opts):
    for kind, option in (("point", "--point-light"), ("spot", "--spot-light")):
        mine = [l for l in lights if l["type"] == kind]
        if bool(mine) != (option in opts) or len(mine) > 1:
            fail(scene, f"{len(mine)} Mirage {kind} light(s), Cycles {option}: {opts.get(option)}")
        if not mine:
            continue
        v = numbers(opts[option])
        if not close(v[:3], mine[0]["position"]):
            fail(scene, f"Cycles' {kind} light at {v[:3]}, Mirage's at {mine[0]['position']}")
        if kind == "spot":
            if not close(unit(v[3:6]), unit(mine[0]["direction"])):
                fail(scene, f"Cycles' spot aims along {v[3:6]}, Mirage's {mine[0]['direction']}")
            if not close([v[7]], [2.0 * mine[0]["cone_angle"]]):
                fail(scene, f"Cycles' cone {v[7]}° across, Mirage's half angle "
                            f"{mine[0]['cone_angle']}°")


def check_dome(scene, lights, opts, sets):
    domes = [l for l in lights if l["type"] == "dome"]
    world = "--world-color" in opts or "--world-hdr" in opts
    if bool(domes) != world or len(domes) > 1:
        fail(scene, f"{len(domes)} Mirage dome(s), Cycles world {world}")
    if not domes:
        return
    if "--world-color" in opts:
        if "map" in domes[0] or not close(numbers(opts["--world-color"]), domes[0]["color"]):
            fail(scene, f"Cycles' world {opts['--world-color']}, Mirage's dome {domes[0]}")
        return
    mirage_map = dict(s.split("=", 1) for s in sets).get("light.0.map", domes[0].get("map", ""))
    if (os.path.basename(opts["--world-hdr"]) != "sky.cycles.hdr"
            or os.path.basename(mirage_map) != "sky.mirage.hdr"):
        fail(scene, f"the HDR worlds are not pipeline/sky_hdr.py's one sky: Cycles "
                    f"{opts['--world-hdr']}, Mirage {mirage_map}")


def check(argv):
    scene, cycles_vdb = argv[0], argv[1]
    split = argv.index("--")
    meta = dict(kv.split("=", 1) for kv in argv[2:split])
    try:
        opts = cycles_options(argv[split + 1:])
    except (ValueError, IndexError) as e:
        fail(scene, f"race.cycles: {e}")
    check_metadata(scene, meta)
    unknown = set(opts) - known_options(cycles_vdb)
    if unknown:
        fail(scene, f"race.cycles: {sorted(unknown)} are not options of {cycles_vdb}")
    with open(scene, "rb") as f:
        doc = tomllib.load(f)
    lights = doc.get("light", [])
    check_medium(scene, doc, opts)
    check_sun(scene, lights, opts)
    check_lamps(scene, lights, opts)
    check_dome(scene, lights, opts, meta.get("set", "").split())
    return f"{scene}: ok"


def self_test():
    """A spot in smoke, checked as race.sh would, then each disagreement the check exists for."""
    with tempfile.TemporaryDirectory() as tmp:
        scene, shader, tool = (os.path.join(tmp, n) for n in ("s.toml", "m.toml", "c.py"))
        with open(shader, "w") as f:
            f.write('[[component]]\ngrid = "density"\nsigma_a = 0.1\nsigma_s = 0.9\ng = 0.3\n')
        with open(scene, "w") as f:
            f.write('[[volume]]\nfile = "a.vdb"\nshader = "m.toml"\ndensity_scale = 0.5\n'
                    '[[light]]\ntype = "spot"\nposition = [1, 2, 3]\ndirection = [0, 2, 0]\n'
                    'cone_angle = 25.0\n')
        with open(tool, "w") as f:
            f.write("".join(f'p.add_argument("--{o}")\n' for o in (
                "density-scale", "albedo", "anisotropy", "sun-strength", "spot-light")))
        meta = [scene, tool, "cache=a.vdb", "cycles=…", "bounces=64", "rows=volpath", "--"]
        good = ["--density-scale", "0.5", "--albedo", "0.9", "--anisotropy", "0.3",
                "--sun-strength", "0", "--spot-light=1,2,3,0,1,0,100,50"]
        assert check(meta + good).endswith(": ok")
        for bad, why in ((["--density-scale", "5"], "--density-scale"),
                         (["--spot-light=1,2,3,0,-1,0,100,50"], "aims along"),
                         (["--spot-light=1,2,3,0,1,0,100,25"], "cone"),
                         (["--sun-strength", "5"], "Mirage none"),
                         (["--spotlight=1,2,3,0,1,0,100,50"], "not options")):
            try:
                check(meta + good + bad)
                raise AssertionError(f"{bad} passed")
            except SystemExit as e:
                assert why in str(e.code), (bad, e.code)
        try:
            check(meta[:5] + ["rows=volpath pt", "--"] + good)
            raise AssertionError("an unknown row passed")
        except SystemExit as e:
            assert "unknown" in str(e.code), e.code
    print("race_scene_check self-test: ok")


def main():
    argv = sys.argv[1:]
    if argv == ["--self-test"]:
        self_test()
        return
    if "--" not in argv or len(argv) < 3:
        sys.exit(__doc__.split("Usage: ")[1])
    print(check(argv))


if __name__ == "__main__":
    main()
