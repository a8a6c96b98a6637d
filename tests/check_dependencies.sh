#!/usr/bin/env bash
# A library that builds and runs with neither Gmsh nor TetGen (docs/ARCHITECTURE.md: core, and
# module with what it stands on): no object includes gmsh.h or tetgen.h (the compiler's
# dependency files say what each object really included), no test executable's link line names
# libgmsh, libtet or a Strata library that links them (CMake's link.txt beside the objects), none
# links them at run time (ldd), and none holds a Gmsh or TetGen symbol (nm).
#   check_dependencies.sh LABEL DEPFILE_DIR... -- EXECUTABLE...
set -uo pipefail
label=$1
shift
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
links=$(find "${dirs[@]}" -name link.txt 2>/dev/null)
forbidden='libgmsh|-lgmsh|libtet|-ltet|libstrata_(io|surface|hybrid|gmsh_api|frontend)\.a'
for l in $links; do
  if grep -Eq "$forbidden" "$l"; then
    echo "$l: the link line names $(grep -Eo "[^ ]*($forbidden)[^ ]*" "$l" | sort -u | tr '\n' ' ')"
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
[ $status -eq 0 ] && echo "$label: $(echo "$depfiles" | wc -l) objects, $(echo "$links" | grep -c .) link lines and $# executables free of Gmsh and TetGen"
exit $status
