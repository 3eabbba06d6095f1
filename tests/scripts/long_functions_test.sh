#!/usr/bin/env bash
# The style guide's "a function you can read on one screen": no function outside tests longer
# than 80 lines (scripts/long_functions.sh, Universal Ctags). Also checks that the checker
# finds a long function, so the test can fail.
#   $1 = phyir binary (unused), $2 = scratch folder (emptied).
set -euo pipefail
work=$2
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
die() { echo "FAIL: $*" >&2; exit 1; }
command -v ctags > /dev/null || die "ctags not found (scripts/install_deps.sh installs universal-ctags)"
rm -rf "$work" && mkdir -p "$work"

# The checker itself: an 85-line function in a scratch repository is found.
git -C "$work" init -q
{
  echo "int long_one(int x) {"
  for i in $(seq 1 83); do echo "  x += $i;"; done
  echo "  return x;"
  echo "}"
  echo "int short_one() { return 1; }"
} > "$work/long.cpp"
mkdir -p "$work/scripts" && cp "$root/scripts/long_functions.sh" "$work/scripts/"
git -C "$work" add long.cpp scripts
if out=$("$work/scripts/long_functions.sh"); then die "the checker missed an 86-line function"; fi
grep -q "^86 long.cpp:1 long_one$" <<< "$out" || die "the checker reported: $out"
grep -q "short_one" <<< "$out" && die "the checker reported a short function: $out"

# The toolkit.
if ! out=$("$root/scripts/long_functions.sh"); then die "functions over 80 lines:
$out"; fi
echo "long functions: OK"
