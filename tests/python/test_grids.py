"""Grids in memory: mirage.Grid (numpy) and pyopenvdb grids as a volume's `file` in a scene dict
give the bits of the same grids read from a file; their errors name the volume's key; their files
go with the scene."""
import copy
import gc
import glob
import os

import numpy as np
import pytest

import mirage
from conftest import FOG_SCENE, run_mirage

vdb = pytest.importorskip("pyopenvdb")  # Debian's python3-openvdb (pipeline/install-deps.sh)


def with_file(file, **volume):
    """FOG_SCENE with its volume reading `file` (a path or grids in memory)."""
    scene = copy.deepcopy(FOG_SCENE)
    scene["volume"][0]["file"] = file
    scene["volume"][0].update(volume)
    del scene["output"]
    return scene


def as_grid(openvdb_grid):
    """A pyopenvdb grid as mirage.Grid: its active box as an array, placed by its transform."""
    lo, hi = openvdb_grid.evalActiveVoxelBoundingBox()
    shape = tuple(h - l + 1 for l, h in zip(lo, hi))
    if isinstance(openvdb_grid, vdb.Vec3SGrid):
        shape += (3,)
    values = np.zeros(shape, np.float32)
    openvdb_grid.copyToArray(values, ijk=lo)
    xf = openvdb_grid.transform
    return mirage.Grid(values, voxel_size=xf.voxelSize()[0], offset=lo,
                       origin=xf.indexToWorld((0, 0, 0)))


def beauty(scene_dict, **render):
    return mirage.render(mirage.Scene.from_dict(scene_dict), **render).beauty


@pytest.fixture(scope="module")
def fog_grid(fog_dir):
    return vdb.read(str(fog_dir / "fog_sphere.vdb"), "density")


def test_a_numpy_grid_renders_the_bits_of_its_file(fog_dir, fog_grid):
    from_file = beauty(with_file(str(fog_dir / "fog_sphere.vdb")))
    grid = as_grid(fog_grid)
    assert grid.offset != (0, 0, 0) or grid.values.shape != (32, 32, 32)  # a real placement
    from_numpy = beauty(with_file({"density": grid}))
    assert from_file.max() > 0.01
    assert np.array_equal(from_file, from_numpy)


def test_a_pyopenvdb_grid_renders_the_bits_of_its_file(fog_dir, fog_grid):
    from_file = beauty(with_file(str(fog_dir / "fog_sphere.vdb")))
    assert np.array_equal(from_file, beauty(with_file({"density": fog_grid})))
    named = fog_grid.copy()
    named.name = "density"
    assert np.array_equal(from_file, beauty(with_file([named])))
    assert fog_grid.name == "density"  # the caller's grid keeps its name


@pytest.fixture(scope="module")
def smoke_path(tmp_path_factory):
    """The smoke asset (density, temperature and its velocity `vel`) at 16 voxels."""
    path = str(tmp_path_factory.mktemp("smoke") / "smoke.vdb")
    r = run_mirage("make-asset", "smoke", "-o", path, "--resolution", "16")
    assert r.returncode == 0, r.stderr
    return path


def test_a_velocity_from_numpy_blurs_as_the_files(smoke_path):
    """A [x, y, z, 3] array is a vector grid: the smoke asset's velocity, blurred by a shutter."""
    path = smoke_path
    density, vel = vdb.read(path, "density"), vdb.read(path, "vel")
    scene = with_file(path, velocity="vel", velocity_scale=20.0)
    scene["camera"]["shutter"] = [-0.5, 0.5]
    still = copy.deepcopy(scene)
    still["camera"]["shutter"] = [0.0, 0.0]
    from_file = beauty(scene)
    from_numpy = beauty(with_file({"density": as_grid(density), "vel": as_grid(vel)},
                                  velocity="vel", velocity_scale=20.0) | {"camera": scene["camera"]})
    assert np.array_equal(from_file, from_numpy)
    assert not np.array_equal(from_file, beauty(still))  # the velocity does blur


def test_a_reload_reads_no_velocity_again(smoke_path):
    """A render with other settings loads the scene again: its density and velocity come from
    the scene's grid cache, not the file."""
    scene_dict = with_file(smoke_path, velocity="vel")
    scene_dict["camera"]["shutter"] = [-0.25, 0.25]
    scene = mirage.Scene.from_dict(scene_dict)
    reads = scene.grid_reads
    assert reads == 2  # the density, then the velocity
    mirage.render(scene, spp=1)
    mirage.render(scene, spp=2)
    assert scene.grid_reads == reads


def test_a_grid_places_its_voxels_by_offset_and_origin():
    """One voxel's place: a cube of 4³ voxels of 0.25 m is the unit cube, wherever its array
    sits in index space, once origin + voxel_size · offset is the same point."""
    values = np.ones((4, 4, 4), np.float32)
    a = mirage.Scene.from_dict(with_file({"density": mirage.Grid(values, 0.25)})).info()
    b = mirage.Scene.from_dict(with_file({"density": mirage.Grid(
        values, 0.25, offset=(8, -4, 2), origin=(-2.0, 1.0, -0.5))})).info()
    box_a, box_b = a["volumes"][0]["world_bounds"], b["volumes"][0]["world_bounds"]
    assert np.allclose(box_a, box_b)
    assert np.allclose(box_a, [[0, 0, 0], [1, 1, 1]], atol=0.26)


def test_a_volumes_precision_passes_through_the_dict():
    """`precision` is a volume key like any other: the grids are held at it, and info() gives
    the tree's bytes at every precision (docs/scene-file.md, "Grid precision")."""
    values = np.linspace(0.0, 1.0, 16 ** 3, dtype=np.float32).reshape((16, 16, 16))
    info = mirage.Scene.from_dict(with_file({"density": mirage.Grid(values, 0.1)},
                                            precision="fp8")).info()
    slot = info["volumes"][0]["slots"][0]
    assert slot["precision"] == "fp8"
    assert slot["tree_bytes"] == slot["tree_bytes_at"]["fp8"] < slot["tree_bytes_at"]["float"]


def test_the_files_go_with_the_scene_and_the_dict_stays(fog_grid):
    before = set(glob.glob("/tmp/mirage-grids-*"))
    scene_dict = with_file({"density": fog_grid})
    kept = copy.deepcopy({k: v for k, v in scene_dict.items() if k != "volume"})
    scene = mirage.Scene.from_dict(scene_dict)
    made = set(glob.glob("/tmp/mirage-grids-*")) - before
    assert len(made) == 1
    assert scene_dict["volume"][0]["file"]["density"] is fog_grid  # not replaced by a path
    assert {k: v for k, v in scene_dict.items() if k != "volume"} == kept
    mirage.render(scene)
    del scene
    gc.collect()
    assert not (set(glob.glob("/tmp/mirage-grids-*")) - before)


def test_bad_grids_raise_errors_naming_the_key(fog_grid):
    with pytest.raises(mirage.Error, match=r"volume\.0\.file\.density.*bare numpy array"):
        mirage.Scene.from_dict(with_file({"density": np.ones((4, 4, 4))}))
    with pytest.raises(mirage.Error, match=r"values of shape \(4, 4\)"):
        mirage.Grid(np.ones((4, 4)), 0.1)
    with pytest.raises(mirage.Error, match="voxel_size"):
        mirage.Grid(np.ones((4, 4, 4)), 0.0)
    bad = np.ones((4, 4, 4), np.float32)
    bad[1, 2, 3] = np.inf
    with pytest.raises(mirage.Error,
                       match=r"'volume\.0\.file': grid 'density': value inf at \[1, 2, 3\]"):
        mirage.Scene.from_dict(with_file({"density": mirage.Grid(bad, 0.1)}))
    with pytest.raises(mirage.Error, match="mixes mirage.Grid and pyopenvdb"):
        mirage.Scene.from_dict(with_file({"density": fog_grid,
                                          "t": mirage.Grid(np.ones((2, 2, 2)), 0.1)}))
    unnamed = vdb.FloatGrid()
    with pytest.raises(mirage.Error, match=r"volume\.0\.file\.0' has no name"):
        mirage.Scene.from_dict(with_file([unnamed]))
    with pytest.raises(mirage.Error, match=r"volume\.0\.file' is a mirage.Grid, which has no name"):
        mirage.Scene.from_dict(with_file(mirage.Grid(np.ones((2, 2, 2)), 0.1)))
    with pytest.raises(mirage.Error, match=r"volume\.0\.file\.density.*is a str"):
        mirage.Scene.from_dict(with_file({"density": "density.vdb"}))
    # A grid the shader needs and the dict lacks: the loader's own message (a lone grid would be
    # bound whatever its name, as a file's only grid is).
    with pytest.raises(mirage.Error, match="no grid 'density'"):
        mirage.Scene.from_dict(with_file({"smoke": fog_grid, "heat": fog_grid}))
