"""Mirage, a spectral volume renderer, from Python (docs/python.md).

    import mirage
    scene = mirage.load("shot.toml", set={"film.spp": 64})
    img = mirage.render(scene, seed=3)
    img.beauty            # numpy float32, H x W x 4, the working space
    img.write("out.exr")  # the EXR `mirage render` writes
"""
from ._mirage import Error, Grid, Image, Scene, Session, __version__, load, read, render

__all__ = ["Error", "Grid", "Image", "Scene", "Session", "load", "read", "render", "__version__"]
