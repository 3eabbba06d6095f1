#!/usr/bin/env bash
# Functions longer than a screen (default 80 lines) outside tests, longest first: the
# style guide's "a function you can read on one screen" (docs/contributing.md). Uses
# Universal Ctags' end-line field; prints "lines file:line name" and exits 1 if any.
set -euo pipefail
limit=${1:-80}
cd "$(dirname "$0")/.."
git ls-files '*.cpp' '*.h' ':!tests' ':!fuzz' |
  ctags --languages=C++ --kinds-C++=f --fields=+ne --extras=-F -L - -o - |
  awk -F'\t' -v limit="$limit" '{
      line = ""; end = "";
      for (i = 4; i <= NF; ++i) {
        if ($i ~ /^line:/) line = substr($i, 6);
        if ($i ~ /^end:/) end = substr($i, 5);
      }
      if (line != "" && end != "" && end - line + 1 > limit)
        printf "%d %s:%s %s\n", end - line + 1, $2, line, $1
    }' | sort -rn | { out=$(cat); [ -z "$out" ] && exit 0; echo "$out"; exit 1; }
