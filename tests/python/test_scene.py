"""mirage.load, mirage.Scene.from_dict and scene.info(): the scene file's loader and errors."""
import numpy as np
import pytest

import mirage
from conftest import FOG_SCENE, run_mirage


def test_load_and_info(fog_scene_path):
    scene = mirage.load(fog_scene_path, set={"film.spp": 2})
    info = scene.info()
    assert info["film"]["spp"] == 2
    assert info["film"]["resolution"] == (24, 24)
    assert info["integrator"] == "volpath"
    assert info["physics"]["multiple scattering"]["active"] in (True, False)
    volume = info["volumes"][0]
    assert volume["shader"] == "smoke"
    assert volume["slots"][0]["active_voxels"] > 0
    assert volume["vdb"]["grids"][0]["name"] == "density"
    assert len(info["lights"]) == 2
    assert scene.source == fog_scene_path


def test_info_names_the_physics_terms_of_mirage_info(fog_scene_path):
    printed = run_mirage("info", fog_scene_path).stdout
    for name, term in mirage.load(fog_scene_path).info()["physics"].items():
        assert name in printed
        assert term["why"] in printed


def test_a_missing_file_raises_the_commands_message(tmp_path):
    missing = str(tmp_path / "missing.toml")
    with pytest.raises(mirage.Error) as e:
        mirage.load(missing)
    cli = run_mirage("info", missing)
    assert cli.returncode == 1
    assert cli.stderr.strip() == "mirage: error: " + str(e.value)


def test_a_bad_set_key_raises_the_commands_message(fog_scene_path):
    with pytest.raises(mirage.Error) as e:
        mirage.load(fog_scene_path, set={"film.spp": 0})
    cli = run_mirage("info", fog_scene_path, "--set", "film.spp=0")
    assert cli.stderr.strip() == "mirage: error: " + str(e.value)
    assert "spp" in str(e.value)


def test_set_values_keep_their_types(fog_scene_path):
    scene = mirage.load(fog_scene_path, set={"output.path": "1.exr", "film.resolution": (8, 6)})
    info = scene.info()
    assert info["output"]["path"].endswith("/1.exr")
    assert info["film"]["resolution"] == (8, 6)
    with pytest.raises(mirage.Error, match="film.seed"):
        mirage.load(fog_scene_path, set={"film.seed": None})


def test_a_dict_is_the_scene_file(fog_dir, fog_scene_path):
    from_file = mirage.render(mirage.load(fog_scene_path))
    from_dict = mirage.render(mirage.Scene.from_dict(FOG_SCENE, base_dir=str(fog_dir)))
    assert np.array_equal(from_file.beauty, from_dict.beauty)
    assert from_dict.metadata["mirage:scene"].endswith("<dict>")


def test_a_dict_takes_the_files_keys_and_errors(fog_dir):
    bad = dict(FOG_SCENE, camera=dict(FOG_SCENE["camera"], fovv=30.0))
    with pytest.raises(mirage.Error, match="fovv"):
        mirage.Scene.from_dict(bad, base_dir=str(fog_dir))
    with pytest.raises(mirage.Error, match="film.spp"):
        mirage.Scene.from_dict(dict(FOG_SCENE, film={"spp": None}), base_dir=str(fog_dir))
    # Relative paths resolve from base_dir: elsewhere the grid file is missing.
    with pytest.raises(mirage.Error, match="fog_sphere.vdb"):
        mirage.Scene.from_dict(FOG_SCENE, base_dir="/nonexistent")


def test_numpy_scalars_are_numbers(fog_dir):
    scene = mirage.Scene.from_dict(
        dict(FOG_SCENE, film={"resolution": [np.int64(8), np.int32(8)], "spp": np.int64(1)}),
        base_dir=str(fog_dir))
    assert scene.info()["film"]["resolution"] == (8, 8)
