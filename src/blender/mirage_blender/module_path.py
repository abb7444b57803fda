"""Where the add-on finds `import mirage`: the built module's folder (<build>/python), from the
add-on's preferences, else from the file `mirage_python_path.txt` beside the add-on, which
pipeline/install-blender-addon.sh writes; unless Blender's Python imports it already."""
import os
import sys

PATH_FILE = os.path.join(os.path.dirname(__file__), "mirage_python_path.txt")


def recorded_dir():
    try:
        with open(PATH_FILE, encoding="utf-8") as f:
            return f.read().strip()
    except OSError:
        return ""


def import_mirage(preferred_dir=""):
    """The mirage module; ImportError with what was tried when it cannot be found."""
    tried = []
    for d in (preferred_dir, recorded_dir()):
        if d and d not in sys.path and os.path.isdir(os.path.join(d, "mirage")):
            sys.path.insert(0, d)
        if d:
            tried.append(d)
    try:
        import mirage
    except ImportError as e:
        raise ImportError(
            "cannot import the Mirage Python module (tried: " + (", ".join(tried) or "nothing") +
            "); set its folder, <build>/python, in the add-on's preferences or run "
            "pipeline/install-blender-addon.sh: " + str(e)) from e
    return mirage
