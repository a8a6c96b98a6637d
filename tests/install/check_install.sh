#!/usr/bin/env bash
# Install this build into a scratch prefix, then configure, build and run a separate CMake
# project that finds it with find_package(strata) and links strata::hybrid and strata::surface:
# the exported targets carry their dependencies (Eigen, OpenMP, nanoflann, Gmsh, TetGen's header).
#   check_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
mkdir "$scratch/consumer"
cat >"$scratch/consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.20)
project(consumer CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(strata REQUIRED)
add_executable(consumer main.cpp)
target_link_libraries(consumer PRIVATE strata::hybrid strata::surface)
CMAKE
cat >"$scratch/consumer/main.cpp" <<'CPP'
// A closed sphere surface through the installed headers and libraries: layers, tetrahedra,
// validation (build_hybrid_mesh throws if the mesh is not valid); the surface stage's header.
#include <strata/geometry/primitives.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/surface/prepare.h>
#include <cstdio>
int main() {
    const strata::SurfaceMesh wall = strata::icosphere(strata::Vec3::Zero(), 1.0, 2, {"wall", strata::PatchKind::Wall});
    strata::HybridParams p;
    p.layers.distribution.layers = 2;
    p.layers.distribution.first_height = 1e-2;
    const strata::VolumeMesh mesh = strata::build_hybrid_mesh(wall, p);
    std::printf("%zu nodes\n", mesh.points.size());
    return mesh.points.empty() ? 1 : 0;
}
CPP
cmake -S "$scratch/consumer" -B "$scratch/consumer/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/consumer/build" >/dev/null
"$scratch/consumer/build/consumer"
