"""Loads the add-on from the repository (src/blender), not from the user's configuration, and
registers it; the module `mirage` from MIRAGE_PYTHON_DIR (the build's python folder). Imported
by the tests' Blender scripts, or run as one before Blender's own arguments:
    blender -b FILE.blend --python addon_from_source.py -E MIRAGE -a"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def load():
    sys.path.insert(0, os.path.join(HERE, "..", "..", "src", "blender"))
    if os.environ.get("MIRAGE_PYTHON_DIR"):
        sys.path.insert(0, os.environ["MIRAGE_PYTHON_DIR"])
    import mirage_blender
    mirage_blender.register()
    return mirage_blender


if __name__ == "__main__":
    load()
