#!/usr/bin/env bash
# `phyir scenes sky` end to end: --help, an EXR written (OpenEXR magic), the sun's lines on
# stdout, the same bytes twice, a different sky for another sun, out-of-range values refused
# naming them.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail

phyir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"

step() { echo "== $*"; }
die() { echo "FAIL: $*" >&2; exit 1; }

step "--help"
"$phyir" scenes sky --help >"$work/help.txt"
for flag in --out --turbidity --sun-elevation --sun-azimuth --width --ground-albedo; do
  grep -q -- "$flag" "$work/help.txt" || die "--help does not mention $flag"
done

step "a sky and its sun"
"$phyir" scenes sky --out "$work/a/sky.exr" --width 64 --turbidity 2.5 --sun-elevation 40 --sun-azimuth 30 >"$work/a.txt"
[ "$(od -An -tx1 -N4 "$work/a/sky.exr" | tr -d ' ')" = "762f3101" ] || die "sky.exr is not an OpenEXR file"
grep -q "sun as KHR_lights_punctual: directional, intensity .* lx" "$work/a.txt" || die "no sun light line: $(cat "$work/a.txt")"
grep -q "sun direction (towards the sun): (0.383, 0.6428, -0.6634)" "$work/a.txt" || die "wrong sun direction: $(cat "$work/a.txt")"

step "same arguments, same bytes; another sun, another sky"
"$phyir" scenes sky --out "$work/b/sky.exr" --width 64 --turbidity 2.5 --sun-elevation 40 --sun-azimuth 30 >/dev/null
cmp "$work/a/sky.exr" "$work/b/sky.exr" || die "two runs wrote different bytes"
"$phyir" scenes sky --out "$work/c/sky.exr" --width 64 --turbidity 2.5 --sun-elevation 41 --sun-azimuth 30 >/dev/null
if cmp -s "$work/a/sky.exr" "$work/c/sky.exr"; then die "another elevation wrote the same sky"; fi

step "bad values are refused naming them"
bad() {
  local expect=$1; shift
  if "$phyir" scenes sky "$@" 2>"$work/bad.err" >/dev/null; then die "accepted: $*"; fi
  grep -q -- "$expect" "$work/bad.err" || die "the error for '$*' does not say '$expect': $(cat "$work/bad.err")"
}
bad "turbidity is 12" --out "$work/x.exr" --turbidity 12
bad "sun elevation is -5 degrees" --out "$work/x.exr" --sun-elevation -5
bad "ground albedo is 2" --out "$work/x.exr" --ground-albedo 2
bad "width 33 must be even" --out "$work/x.exr" --width 33
bad "write it as .exr" --out "$work/x.png"
bad "out" --width 64
echo "PASS"
