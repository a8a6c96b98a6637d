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
  libnanoflann-dev     # k-d tree (the tetrahedra's size field)
  libcgal-dev          # exact predicates: the layer front's self-intersection test
  libcgns-dev          # CGNS mid-level library (on HDF5): the .cgns writer
  openfoam             # checkMesh, OpenFOAM's verdict on our meshes (tests/openfoam)
  libgtest-dev         # GoogleTest
  libcli11-dev         # command-line parsing for the strata program
)

bash scripts/install_packages.sh setup "${packages[@]}"

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$jobs"

case "$mode" in
  build) ;;
  test)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    ;;
  example)
    mkdir -p out
    # The main job: the ONERA M6 wing from its STEP file to a hybrid mesh (Cobalt60 + patch map).
    "$build_dir"/app/strata mesh examples/data/onera_m6_sharp_te.stp -o out/onera_m6.cgr \
      --size 30 --layers 20 --first-height 0.02 --growth 1.2
    ;;
  *)
    echo "usage: scripts/setup.sh [example|test|build]" >&2
    exit 2
    ;;
esac
