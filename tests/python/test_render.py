"""mirage.render and mirage.Image: the pixels and EXR of `mirage render`, errors, threads, the
GIL, two scenes in one process and memory over repeated renders."""
import threading
import time

import numpy as np
import pytest

import mirage
from conftest import resident_bytes, run_mirage


def test_render_gives_numpy_images_and_the_header(fog_scene_path):
    img = mirage.render(mirage.load(fog_scene_path), seed=3, aovs=["albedo", "alpha"])
    assert img.beauty.shape == (24, 24, 4) and img.beauty.dtype == np.float32
    assert np.isfinite(img.beauty).all() and img.beauty[..., :3].max() > 0
    assert set(img.aovs) == {"albedo", "alpha"}
    assert img.aovs["albedo"].shape[:2] == (24, 24)
    assert img.metadata["mirage:seed"] == "3"
    assert img.metadata["mirage:integrator"] == "volpath"
    assert img.metadata["mirage:complete"] == "true"


@pytest.mark.parametrize("args,kwargs", [
    ([], {}),
    (["--seed", "5", "--spp", "3", "--resolution", "20x16", "--aov", "alpha"],
     {"seed": 5, "spp": 3, "resolution": (20, 16), "aovs": ["alpha"]}),
    (["--passes", "2", "--set", "light.0.irradiance=900"],
     {"passes": 2, "set": {"light.0.irradiance": 900}}),
])
def test_the_exr_is_the_commands(fog_dir, fog_scene_path, tmp_path, args, kwargs):
    cli = str(tmp_path / "cli.exr")
    r = run_mirage("render", fog_scene_path, "-o", cli, "-q", *args)
    assert r.returncode == 0, r.stderr
    scene = mirage.load(fog_scene_path, set=kwargs.pop("set", {}))
    img = mirage.render(scene, **kwargs)
    img.write(str(tmp_path / "py.exr"))
    a, b = mirage.read(cli), mirage.read(str(tmp_path / "py.exr"))
    assert np.array_equal(a.beauty, b.beauty)
    for name in a.aovs:
        assert np.array_equal(a.aovs[name], b.aovs[name])
    timed = ("seconds", "time_spent", "DateTime")
    same = lambda m: {k: v for k, v in m.items() if not any(t in k for t in timed)}
    assert same(a.metadata) == same(b.metadata)


def test_errors_raise_the_commands_messages(fog_scene_path):
    scene = mirage.load(fog_scene_path)
    with pytest.raises(mirage.Error, match="--spp is outside"):
        mirage.render(scene, spp=-1)
    with pytest.raises(mirage.Error) as e:
        mirage.render(scene, integrator="nope")
    cli = run_mirage("render", fog_scene_path, "--integrator", "nope", "-o", "/dev/null")
    assert str(e.value) in cli.stderr
    with pytest.raises(mirage.Error, match="resolution"):
        mirage.render(scene, resolution="big")
    with pytest.raises(TypeError, match="unexpected keyword argument 'sppp'"):
        mirage.render(scene, sppp=4)
    with pytest.raises(mirage.Error):
        mirage.read(fog_scene_path.replace("shot.toml", "nothing.exr"))


def test_thread_counts_give_the_same_bits(fog_scene_path):
    scene = mirage.load(fog_scene_path)
    one = mirage.render(scene, threads=1, spp=2)
    two = mirage.render(scene, threads=2, spp=2)
    assert np.array_equal(one.beauty, two.beauty)


def test_the_gil_is_released_while_rendering(fog_scene_path):
    scene = mirage.load(fog_scene_path)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    start = len(ticks)
    mirage.render(scene, spp=64, threads=1)
    stop.set()
    t.join()
    assert len(ticks) - start > 10


def test_two_scenes_in_one_process(fog_scene_path):
    a = mirage.load(fog_scene_path)
    b = mirage.load(fog_scene_path, set={"light.0.irradiance": 400.0})
    alone_a = mirage.render(a, spp=2).beauty
    alone_b = mirage.render(b, spp=2).beauty
    results = {}
    threads = [threading.Thread(target=lambda k, s: results.__setitem__(k, mirage.render(s, spp=2)),
                                args=(k, s)) for k, s in (("a", a), ("b", b))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results["a"].beauty, alone_a)
    assert np.array_equal(results["b"].beauty, alone_b)
    assert not np.array_equal(alone_a, alone_b)


def test_memory_stays_flat_over_50_renders(fog_scene_path):
    def one():
        scene = mirage.load(fog_scene_path)
        return mirage.render(scene, spp=1, resolution=(16, 16)).beauty.sum()

    for _ in range(10):
        one()
    before = resident_bytes()
    for _ in range(50):
        one()
    grown = resident_bytes() - before
    assert grown < 8 << 20, f"resident set grew by {grown / 2**20:.1f} MiB over 50 renders"
