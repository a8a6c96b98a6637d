#!/usr/bin/env bash
# Fuzz Strata's input and output code with libFuzzer, AddressSanitizer and UBSan (Debian's clang 14):
#   scripts/fuzz.sh [TARGET|all] [SECONDS]   each target asked for SECONDS (default 600)
#   scripts/fuzz.sh smoke [SECONDS [TARGET...]]   CI: every target (or those given) for SECONDS
#                                                 (default 20)
# TARGET is one of
#   stl      the STL reader (read_stl_bytes: ASCII and binary, told apart by content), then the
#            surface chain below on the mesh it read
#   surface  a triangle/quad soup decoded from the bytes (fuzz/fuzz_surface.cpp says how:
#            small node counts, grid coordinates and raw doubles incl. NaN and infinity, faces
#            of 3 or 4 ids, patch ids, options, corrupted arrays) through check_surface,
#            vertex_faces, edge_table, boundary_loops, face_components, node_rings,
#            orient_surface, needle_faces alone and prepare_mesh as a whole (merge, removal of
#            collapsed faces, check, orientation), with its result checked again
#   msh      the bytes as a .msh file (in /dev/shm) through read_msh and read_volume_msh (Gmsh's
#            reader: MSH 4.1 and 2.2, ASCII and binary); a mesh read must pass the array checks
#   writers  a small volume mesh decoded from the bytes (fuzz/volume_soup.cpp: every cell type,
#            boundary faces listed or completed, awkward patch names, corrupted arrays) written as
#            Cobalt60 and CGNS over existing files and read back (tests/io/cobalt_reader.h, the
#            CGNS library): the same nodes bit for bit, cells, boundary faces and patches; or a
#            refusal, only of unsound arrays (or unmatched faces, Cobalt60), leaving the files
# or all (the default: each in turn). Each target runs in one process (one core) with
# -timeout=10 -rss_limit_mb=4096.
#
# smoke is what CI runs after the tests (.ci/run): every target for SECONDS, from the committed
# seeds and reproducers alone; it fails the run on a finding. Measured cold (a new BUILD_DIR, no
# ccache, clang installed) on 2 cores that two other builds shared: 13.5 min for 9 CPU-minutes,
# so about 6 min on 2 free cores; the build of core, io and geometry with the sanitizers is most
# of it, the fuzzing 4 x 20 s. For a real search run a target for minutes or hours:
# scripts/fuzz.sh msh 3600.
#
# The script installs clang and libfuzzer-14-dev if missing (the way scripts/setup.sh installs
# its packages; Strata's other dependencies come from setup.sh), configures BUILD_DIR with
# CXX=clang++ -DSTRATA_FUZZ=ON (every library compiled with the sanitizers and libFuzzer's
# coverage, the targets linked with -fsanitize=fuzzer), builds the targets asked for and only
# the libraries they link (msh and writers: core and io; stl and surface: geometry too), and
# seeds a working corpus (BUILD_DIR/corpus/TARGET, kept between runs) from fuzz/corpus/TARGET
# (small valid inputs, fuzz/make_seeds.py), fuzz/regressions/TARGET and, for stl outside smoke,
# every STL file in SHARED_DATA, examples/data and tests/data.
#
# A finding (a crash, a sanitizer report, an exception other than strata::Error, a failed
# oracle, an input that runs over 10 s or allocates over 4 GB) stops the target; the script
# copies the input into fuzz/regressions/TARGET/, prints the libFuzzer log's tail and exits 1
# once every target asked has run. Reproduce with BUILD_DIR/fuzz/fuzz_TARGET FILE. Fix it so
# that Strata refuses the input with an InputError or a TopologyError naming what is wrong, give
# the file a name that says what it is, and tests/fuzz/test_fuzz_regressions.cpp (normal build,
# CI) replays it from then on. A finding in code Strata cannot fix and does not guard yet (Gmsh's
# readers) goes to fuzz/pending/TARGET/ instead (fuzz/pending/README.md), out of the replay.
#
# Environment: BUILD_DIR (default build-fuzz), SHARED_DATA (default ../shared/data), JOBS
# (build parallelism, default: number of cores), FUZZ_ARGS (more libFuzzer options).
set -euo pipefail

cd "$(dirname "$0")/.."
what=${1:-all}
build_dir=${BUILD_DIR:-build-fuzz}
shared=${SHARED_DATA:-../shared/data}
jobs=${JOBS:-$(nproc)}
all_targets=(msh writers stl surface)

case "$what" in
  smoke) if [ $# -gt 2 ]; then targets=("${@:3}"); else targets=("${all_targets[@]}"); fi ;;
  all) targets=("${all_targets[@]}") ;;
  stl | surface | msh | writers) targets=("$what") ;;
  *)
    echo "usage: scripts/fuzz.sh [stl|surface|msh|writers|all] [SECONDS] | scripts/fuzz.sh smoke [SECONDS [TARGET...]]" >&2
    exit 2
    ;;
esac
for t in "${targets[@]}"; do
  [[ " ${all_targets[*]} " == *" $t "* ]] || { echo "fuzz: no target '$t' (${all_targets[*]})" >&2; exit 2; }
done
if [ "$what" = smoke ]; then seconds=${2:-20}; else seconds=${2:-600}; fi

packages=(clang libfuzzer-14-dev)
bash scripts/install_packages.sh fuzz "${packages[@]}"

# -O1 with line tables (the root CMakeLists.txt adds -gline-tables-only), OSS-Fuzz's flags: line
# numbers in the sanitizers' reports at half the compile time of -O2 -g (geometry's CGAL units).
CC=clang CXX=clang++ cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DSTRATA_FUZZ=ON -DSTRATA_BUILD_TESTS=OFF >/dev/null
cmake --build "$build_dir" -j "$jobs" --target "${targets[@]/#/fuzz_}"

# Per target: the longest input, extra options.
declare -A max_len=([stl]=131072 [surface]=4096 [msh]=8192 [writers]=2048)
# msh: Gmsh (not instrumented) allocates from a file's counts and leaves most of it untouched, as
# it would outside the fuzzer, so only memory used (-rss_limit_mb) is a finding there, not the
# size of one allocation (by default also 4 GB); too large an allocation throws std::bad_alloc
# (allocator_may_return_null), which Strata turns into an InputError as in a normal build. Gmsh
# leaks on every other input, and libFuzzer's leak check of each such input halves the inputs
# run per second, so leaks are not looked for there.
declare -A extra=([stl]="-dict=fuzz/stl.dict" [surface]=""
  [msh]="-dict=fuzz/msh.dict -malloc_limit_mb=1048576 -detect_leaks=0" [writers]="")
export ASAN_OPTIONS=allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1

status=0
for t in "${targets[@]}"; do
  corpus="$build_dir/corpus/$t"
  artifacts="$build_dir/artifacts/$t"
  log="$build_dir/fuzz_$t.log"
  mkdir -p "$corpus" "$artifacts" "fuzz/regressions/$t"
  rm -f "$artifacts"/*
  cp fuzz/corpus/"$t"/* "$corpus"/
  find "fuzz/regressions/$t" -type f -exec cp {} "$corpus"/ \;
  if [ "$t" = stl ] && [ "$what" != smoke ]; then
    for dir in "$shared" examples/data tests/data; do
      [ -d "$dir" ] && find "$dir" -maxdepth 2 -iname '*.stl' -exec cp {} "$corpus"/ \;
    done
  fi
  echo "fuzz: $t for $seconds s, corpus $corpus ($(find "$corpus" -type f | wc -l) files), log $log"
  # shellcheck disable=SC2086  # FUZZ_ARGS and extra are lists of options
  if "$build_dir/fuzz/fuzz_$t" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    -max_len="${max_len[$t]}" -print_final_stats=1 -artifact_prefix="$artifacts/" ${extra[$t]} \
    ${FUZZ_ARGS:-} >"$log" 2>&1; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    done_line=$(grep ' cov: ' "$log" | tail -n 1 || true)
    cov=$(echo "$done_line" | sed -n 's/.* cov: \([0-9]*\).*/\1/p')
    units=$(echo "$done_line" | sed -n 's/.* corp: \([0-9]*\).*/\1/p')
    echo "fuzz: $t ran $seconds s without a finding: $execs inputs run, corpus $units inputs" \
      "($(find "$corpus" -type f | wc -l) files), $cov edges covered"
  else
    status=1
    tail -n 40 "$log"
    for f in "$artifacts"/*; do
      [ -f "$f" ] || continue
      cp "$f" "fuzz/regressions/$t/"
      echo "fuzz: $t: FINDING $(basename "$f") copied to fuzz/regressions/$t/ (reproduce: $build_dir/fuzz/fuzz_$t $f)"
    done
  fi
done
exit $status
