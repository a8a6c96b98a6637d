#!/usr/bin/env bash
# strata::core builds and runs with neither Gmsh nor TetGen (docs/ARCHITECTURE.md): no core
# source nor core test includes gmsh.h or tetgen.h (the compiler's dependency files say what
# each object really included), no core test executable links libgmsh or libtet (ldd), and none
# holds a Gmsh or TetGen symbol (nm).
#   check_core_dependencies.sh DEPFILE_DIR... -- EXECUTABLE...
set -uo pipefail
dirs=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do dirs+=("$1"); shift; done
shift
status=0
depfiles=$(find "${dirs[@]}" -name '*.o.d' 2>/dev/null)
if [ -z "$depfiles" ]; then
  echo "no dependency files (*.o.d) under ${dirs[*]}: build with CMake's Makefile generator and GCC or Clang"
  exit 1
fi
for d in $depfiles; do
  if grep -Eq '(^|[/ ])(gmsh\.h|tetgen\.h)( |$)' "$d"; then
    echo "$d: includes $(grep -Eo '[^ ]*(gmsh|tetgen)\.h' "$d" | sort -u | tr '\n' ' ')"
    status=1
  fi
done
for exe in "$@"; do
  if ldd "$exe" | grep -Eq 'libgmsh|libtet'; then
    echo "$exe links: $(ldd "$exe" | grep -Eo 'lib(gmsh|tet)[^ ]*' | tr '\n' ' ')"
    status=1
  fi
  if nm -C "$exe" | grep -Eq 'gmsh::|tetgenio|tetrahedralize'; then
    echo "$exe holds Gmsh or TetGen symbols"
    status=1
  fi
done
[ $status -eq 0 ] && echo "core: $(echo "$depfiles" | wc -l) objects and $# executables free of Gmsh and TetGen"
exit $status
