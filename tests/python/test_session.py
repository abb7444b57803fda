"""mirage.Session: one image per pass that converges, cancel, KeyboardInterrupt, update."""
import _thread
import threading
import time

import numpy as np
import pytest

import mirage


def rel_error(img, reference):
    d = img.beauty[..., :3] - reference[..., :3]
    return float(np.sqrt((d * d).mean()) / np.abs(reference[..., :3]).mean())


def test_passes_converge_to_the_render(fog_scene_path):
    scene = mirage.load(fog_scene_path, set={"render.pass_spp": 1})
    reference = mirage.render(scene, spp=256).beauty
    with mirage.Session(scene, spp=16) as s:
        images = list(s)
        result = s.result
    assert [int(i.metadata["mirage:passes"]) for i in images] == list(range(1, 17))
    errors = [rel_error(i, reference) for i in images]
    # Noise falls as 1/sqrt(passes): the last pass far below the first, and the trend down.
    assert errors[-1] < 0.5 * errors[0], errors
    assert np.mean(errors[8:]) < np.mean(errors[:8]), errors
    # The finished frame is the last pass, and the render in passes of mirage.render.
    assert np.array_equal(result.beauty, images[-1].beauty)
    assert np.array_equal(result.beauty, mirage.render(scene, passes=16).beauty)
    assert result.final and not images[0].final
    with pytest.raises(mirage.Error, match="not a finished frame"):
        images[0].write("/tmp/never.exr")


def test_cancel_stops_the_render(fog_scene_path):
    scene = mirage.load(fog_scene_path, set={"render.pass_spp": 1})
    s = mirage.Session(scene, spp=100000, resolution=(64, 64))
    first = next(s)
    t0 = time.monotonic()
    s.cancel()
    assert time.monotonic() - t0 < 2.0
    assert s.done
    rest = list(s)  # the passes finished before the cancel, then the end
    assert all(int(i.metadata["mirage:passes"]) > 1 for i in rest)
    assert s.result is None
    assert first.beauty.shape == (64, 64, 4)


def test_keyboard_interrupt_stops_a_session(fog_scene_path):
    # As docs/python.md shows it, in a with block: the interrupt may land in the loop's own
    # Python code between two images (where no library code runs), and leaving the block
    # cancels the render wherever it landed.
    scene = mirage.load(fog_scene_path, set={"render.pass_spp": 1})
    threading.Timer(0.3, _thread.interrupt_main).start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        with mirage.Session(scene, spp=100000, resolution=(64, 64)) as s:
            for _ in s:
                pass
    assert time.monotonic() - t0 < 3.0
    assert s.done


def test_keyboard_interrupt_stops_a_render(fog_scene_path):
    # Tiles of 4x4 pixels: the render stops between tiles, milliseconds apart.
    scene = mirage.load(fog_scene_path, set={"film.tile_size": 4})
    threading.Timer(0.3, _thread.interrupt_main).start()
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        mirage.render(scene, spp=4096, resolution=(128, 128))
    assert time.monotonic() - t0 < 3.0


def test_update_restarts_with_the_edit_and_keeps_the_grids(fog_scene_path):
    scene = mirage.load(fog_scene_path, set={"render.pass_spp": 1})
    with mirage.Session(scene, spp=4) as s:
        before = next(s)
        reads = scene.grid_reads
        s.update({"light.0.irradiance": 3000.0, "camera.fov": 30.0})
        after = list(s)
        assert scene.grid_reads == reads  # the grid file was not read again
        assert s.generation == 1
        assert all(i.generation == 1 for i in after)
        assert len(after) == 4
        edited = mirage.load(fog_scene_path, set={"render.pass_spp": 1, "light.0.irradiance": 3000.0,
                                                  "camera.fov": 30.0})
        assert np.array_equal(after[-1].beauty, mirage.render(edited, passes=4).beauty)
        assert not np.array_equal(after[0].beauty, before.beauty)
        with pytest.raises(mirage.Error, match="nope"):
            s.update({"camera.nope": 1})


def test_a_time_limit_shows_the_coarse_image_first(fog_scene_path):
    scene = mirage.load(fog_scene_path)
    with mirage.Session(scene, time_limit=1.0) as s:
        first = next(s)
        assert first.metadata["mirage:passes"] == "0"
        assert int(first.metadata["mirage:coarse_spp"]) >= 1
        assert first.beauty.shape == (24, 24, 4) and first.beauty[..., :3].max() > 0
        s.cancel()
