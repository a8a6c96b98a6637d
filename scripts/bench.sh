#!/usr/bin/env bash
# Time the boundary-layer module (bench/bench_layers.cpp): configure a Release build, build
# the bench_layers target and run it. Environment: BUILD_DIR (default build).
#   scripts/bench.sh
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" --target bench_layers -j "${JOBS:-$(nproc)}"
"$build_dir/bench/bench_layers"
