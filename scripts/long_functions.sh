#!/usr/bin/env bash
# List the functions longer than N lines (default 120) in Strata's C++ sources, longest first:
#   scripts/long_functions.sh [N]
# Lines are counted from a function's first line to its closing brace (Universal Ctags' end field).
set -euo pipefail
cd "$(dirname "$0")/.."
limit=${1:-120}
git ls-files '*.cpp' '*.h' | grep -v '^fuzz/corpus' |
  xargs ctags --c++-kinds=f --fields=+ne --sort=no -o - 2>/dev/null |
  awk -F'\t' -v limit="$limit" '
    $1 ~ /^__anon/ { next }
    { line = ""; end = ""
      for (i = 4; i <= NF; ++i) {
        if ($i ~ /^line:/) line = substr($i, 6)
        if ($i ~ /^end:/) end = substr($i, 5)
      }
      if (line != "" && end != "" && end - line + 1 > limit) printf "%d\t%s:%s\t%s\n", end - line + 1, $2, line, $1 }' |
  sort -rn
