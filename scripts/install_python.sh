#!/usr/bin/env bash
# Make the Python package strata, built by CMake into BUILD_DIR/python/strata, importable by
# Debian's python3 from any directory, put the strata-gmsh and strata-gmsh-onelab launchers on
# PATH, and list Strata among the solvers of the `gmsh` program for the user who runs this.
#   scripts/install_python.sh BUILD_DIR
# Debian 12 refuses `pip install` into the system Python (PEP 668, "externally managed"), and a
# wheel would freeze a copy that the next build does not update. Instead one file, strata.pth,
# holds the absolute path of BUILD_DIR/python: Python's site module adds it to sys.path at
# start-up. As root it goes where Debian's python3 looks for locally installed packages
# (/usr/local/lib/python3.X/dist-packages), for every user; otherwise into the user's own
# site-packages (python3 -m site --user-site). Uninstall: delete that strata.pth.
# Gmsh reads its solvers from the user's own files only ($GMSH_HOME or $HOME: ~/.gmshrc, then
# ~/.gmsh-options), so the registration is per user: `strata-gmsh-onelab --register` adds one
# marked block to ~/.gmsh-options (again: replaces it), `strata-gmsh-onelab --unregister`
# removes it (docs/USAGE.md, "In stock Gmsh's window").
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=$(cd "${1:-build}" && pwd)
python=/usr/bin/python3
package_dir="$build_dir/python"
[ -f "$package_dir/strata/__init__.py" ] || { echo "install_python: no package in $package_dir (build first)" >&2; exit 1; }

if [ "$(id -u)" -eq 0 ]; then
  site=$($python -c 'import site; print(site.getsitepackages()[0])')
  bin=/usr/local/bin
else
  site=$($python -m site --user-site)
  bin=$HOME/.local/bin
fi
mkdir -p "$site" "$bin"
echo "$package_dir" > "$site/strata.pth"
ln -sf "$PWD/scripts/strata-gmsh" "$bin/strata-gmsh"
ln -sf "$PWD/scripts/strata-gmsh-onelab" "$bin/strata-gmsh-onelab"
# Checked from another directory, as a user would use it.
(cd / && $python -c "import strata, os; assert os.path.dirname(os.path.dirname(strata.__file__)) == '$package_dir'") ||
  { echo "install_python: python3 does not find strata through $site/strata.pth" >&2; exit 1; }
# Strata among the gmsh program's solvers, for this user (optional: a failure only warns)
"$bin/strata-gmsh-onelab" --register "$bin/strata-gmsh-onelab" ||
  echo "install_python: Strata is not listed among Gmsh's solvers (strata-gmsh-onelab --register failed)" >&2
echo "python: strata importable by $python ($site/strata.pth -> $package_dir); launchers $bin/strata-gmsh, $bin/strata-gmsh-onelab"
