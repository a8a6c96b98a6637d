#!/usr/bin/env bash
# Make Strata's FreeCAD module (freecad/StrataMesher) visible to FreeCAD and freecadcmd, so that
# the Python console and scripts can `import strata_freecad` and the GUI shows the Strata
# workbench.
#   scripts/install_freecad.sh
# FreeCAD 0.20 on Debian loads every folder of two Mod directories at start-up (running each
# one's Init.py, and InitGui.py in the GUI, with the folder put on sys.path): its own,
# /usr/share/freecad/Mod (= /usr/lib/freecad/Mod), and the user's,
# ~/.local/share/FreeCAD/Mod (FreeCAD's UserAppData). As root the module goes into the first,
# for every user (dpkg leaves files it does not own alone); otherwise into the user's. It is a
# symlink to this checkout, like the .pth of install_python.sh: edits apply at the next start.
# FREECAD_MOD_DIR overrides the directory. Uninstall: delete that StrataMesher link.
# The strata package itself comes from the .pth file (scripts/install_python.sh): freecadcmd
# runs Debian's /usr/bin/python3.11 and reads the same dist-packages.
set -euo pipefail
cd "$(dirname "$0")/.."
module_dir="$PWD/freecad/StrataMesher"
command -v freecadcmd >/dev/null || { echo "install_freecad: no freecadcmd (Debian package freecad-python3)" >&2; exit 1; }

if [ -n "${FREECAD_MOD_DIR:-}" ]; then
  mod=$FREECAD_MOD_DIR
elif [ "$(id -u)" -eq 0 ]; then
  mod=/usr/share/freecad/Mod
else
  mod=$HOME/.local/share/FreeCAD/Mod
fi
mkdir -p "$mod"
ln -sfn "$module_dir" "$mod/StrataMesher"

# Checked as a user would use it: freecadcmd from another directory imports the module (found
# through the Mod directory) and strata (through the .pth). freecadcmd's exit status does not
# report a failing script, so the script prints a marker line.
check=$(mktemp --suffix=.py)
trap 'rm -f "$check"' EXIT
cat > "$check" <<'PY'
import os, strata, strata_freecad
print("STRATA_FREECAD", os.path.realpath(os.path.dirname(strata_freecad.__file__)), os.path.dirname(strata.__file__))
PY
out=$(cd / && timeout 120 freecadcmd "$check" 2>&1 || true)
line=$(grep '^STRATA_FREECAD ' <<<"$out" || true)
if [ -z "$line" ] || [ "$(cut -d' ' -f2 <<<"$line")" != "$module_dir" ]; then
  echo "install_freecad: freecadcmd does not import strata_freecad from $mod/StrataMesher:" >&2
  tail -5 <<<"$out" >&2
  exit 1
fi
echo "freecad: module $mod/StrataMesher -> $module_dir; strata from $(cut -d' ' -f3 <<<"$line")"
