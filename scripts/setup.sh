#!/usr/bin/env bash
# Strata's one entry point on a fresh Debian 12 machine: install every dependency from
# Debian's packages (idempotent), configure and build, then
#   scripts/setup.sh example   run the main job on a bundled example (the default)
#   scripts/setup.sh test      run the test suite (what .ci/run calls)
#   scripts/setup.sh build     only install and build
# Environment: BUILD_DIR (default build), JOBS (default: number of cores).
set -euo pipefail

cd "$(dirname "$0")/.."
mode=${1:-example}
build_dir=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}

# Debian packages Strata builds against (see README, "Dependencies").
packages=(
  build-essential cmake pkg-config
  libgmsh-dev          # Gmsh SDK 4.8 with OpenCASCADE: CAD import, surface meshing, .msh I/O
  libeigen3-dev        # small dense linear algebra
  libtet1.5-dev        # TetGen 1.5 (tetrahedral fill)
  libnanoflann-dev     # k-d trees (the tetrahedra's size field, the CAD walls' sizes at the layers' steps)
  libcgal-dev          # exact predicates: the layer front's self-intersection test
  libcgns-dev          # CGNS mid-level library (on HDF5): the .cgns writer
  openfoam             # checkMesh, OpenFOAM's verdict on our meshes, and simpleFoam on Strata's case (tests/openfoam)
  libgtest-dev         # GoogleTest
  libcli11-dev         # command-line parsing for the strata program
  # The Python package strata (python/, for Debian's /usr/bin/python3):
  python3-dev          # Python 3.11 headers for the extension module
  pybind11-dev         # C++ <-> Python bindings (found by CMake: find_package(pybind11 CONFIG))
  python3-numpy        # the meshes' arrays are NumPy views
  python3-gmsh         # Gmsh's Python API on the same libgmsh: strata.gmsh, strata.gmsh_gui
  python3-pytest       # the package's tests (tests/python)
  xvfb xauth           # a virtual display for the Gmsh-window tests of strata-gmsh and strata-gmsh-onelab (tests/python)
  gmsh                 # the gmsh program (4.8.4, on the same libgmsh) in which Strata is a ONELAB solver (strata-gmsh-onelab)
  xdotool              # clicks in that program's window in its test, as a user would (tests/python/test_gmsh_onelab.py)
  # FreeCAD 0.20 for Strata's FreeCAD module (freecad/, tests/freecad): freecad-python3 holds
  # freecadcmd and the GUI; it is what the metapackage `freecad` depends on, without the
  # metapackage's recommends (CalculiX, Graphviz). Still large: 206 packages, ~1.5 GB
  # installed on a machine that already had the packages above (Qt 5, PySide2, VTK 9, Coin).
  freecad-python3
  python3-matplotlib   # the quality report's plots: strata report, strata mesh --plots (strata.report)
  python3-vtk9         # VTK's own XML readers read Strata's .vtu/.vtm back in the tests (tests/io/read_vtk.py)
  snakemake            # the workflow meshing a family of variants (examples/pipeline) and its test
  slurm-wlm munge      # Slurm 22.05 (slurmctld, slurmd, sbatch) and munge: the workflow's test on a one-node Slurm
  time bc              # /usr/bin/time (peak memory) and bc (seconds) in the measuring scripts and their test
)

bash scripts/install_packages.sh setup "${packages[@]}"

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$jobs"
# import strata from any directory (a .pth file pointing at the build tree; see the script)
bash scripts/install_python.sh "$build_dir"
# import strata_freecad in FreeCAD and freecadcmd (a symlink into FreeCAD's Mod folder; see the script)
bash scripts/install_freecad.sh

# The main job: the ONERA M6 wing from its STEP file to a hybrid mesh (Cobalt60 + patch map).
run_example() {
  mkdir -p out
  "$build_dir"/app/strata mesh examples/data/onera_m6_sharp_te.stp -o out/onera_m6.cgr \
    --size 30 --layers 20 --first-height 0.02 --growth 1.2
}

case "$mode" in
  build) ;;
  test)
    # What the first command does after the build, so CI runs both commands of the README.
    run_example
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    # The Python package, on the build tree's package (tests/python/conftest.py).
    BUILD_DIR="$build_dir" /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python
    # The libFuzzer targets for 20 s each from their seeds, in a sanitizer build of their own
    # (scripts/fuzz.sh smoke; clang). Not the msh target: Strata's build reads a .msh in a child
    # first, where Gmsh 4.8's reader may crash (fuzz/regressions/msh, replayed by the tests), but
    # the fuzz build cannot fork beside Gmsh (clang's OpenMP runtime) and crashes on those files.
    BUILD_DIR="$build_dir-fuzz" bash scripts/fuzz.sh smoke 20 writers stl surface
    ;;
  example) run_example ;;
  *)
    echo "usage: scripts/setup.sh [example|test|build]" >&2
    exit 2
    ;;
esac
