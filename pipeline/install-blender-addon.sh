#!/usr/bin/env bash
# Installs and enables the Mirage render engine in the user's Blender (docs/blender.md).
# Usage: pipeline/install-blender-addon.sh [BUILD_DIR]   (default build; run pipeline/build.sh
# or pipeline/demo.sh first, which build the Python module into BUILD_DIR/python)
# Installs Blender with pipeline/install-deps.sh when it is missing; copies
# src/blender/mirage_blender into Blender's user add-ons folder with a file naming the
# module's folder (re-run after pulling to update it); enables it and saves the preferences.
# Blender's own BLENDER_USER_SCRIPTS / BLENDER_USER_CONFIG choose another user folder.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
MODULE_DIR=$(cd "$BUILD_DIR" 2>/dev/null && pwd)/python
if [ ! -f "$MODULE_DIR/mirage/__init__.py" ]; then
  echo "install-blender-addon: no Python module in $BUILD_DIR/python; run pipeline/build.sh $BUILD_DIR first" >&2
  exit 1
fi
command -v blender >/dev/null || pipeline/install-deps.sh

# Blender's user add-ons folder, as this Blender computes it.
ADDONS=$(blender -b --factory-startup --python-expr \
  "import bpy; print('ADDONS=' + bpy.utils.user_resource('SCRIPTS', path='addons', create=True))" \
  2>/dev/null | sed -n 's/^ADDONS=//p')
[ -n "$ADDONS" ] || { echo "install-blender-addon: Blender did not name its add-ons folder" >&2; exit 1; }
rm -rf "$ADDONS/mirage_blender"
cp -r src/blender/mirage_blender "$ADDONS/mirage_blender"
printf '%s\n' "$MODULE_DIR" > "$ADDONS/mirage_blender/mirage_python_path.txt"

# Enabled in the saved preferences, then checked from a fresh start: the engine is there and
# the module imports in Blender's Python.
blender -b --python-exit-code 1 --python-expr "
import bpy
bpy.ops.preferences.addon_enable(module='mirage_blender')
bpy.context.preferences.addons['mirage_blender'].preferences.python_dir = '$MODULE_DIR'
bpy.ops.wm.save_userpref()
" >/dev/null
blender -b --python-exit-code 1 --python-expr "
import bpy, sys
assert 'MIRAGE' in {c.bl_idname for c in bpy.types.RenderEngine.__subclasses__()}, 'no MIRAGE engine'
from mirage_blender import module_path
m = module_path.import_mirage(bpy.context.preferences.addons['mirage_blender'].preferences.python_dir)
print('MIRAGE_ADDON ok: mirage', m.__version__)
" 2>&1 | grep -q "MIRAGE_ADDON ok" || { echo "install-blender-addon: the add-on does not load; run blender -b --python-expr 'import mirage_blender' to see why" >&2; exit 1; }
echo "install-blender-addon: Mirage enabled in Blender ($ADDONS/mirage_blender, module $MODULE_DIR)"
echo "  Render Properties > Render Engine > Mirage; headless: blender -b shot.blend -E MIRAGE -f 1"
