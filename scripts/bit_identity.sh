#!/usr/bin/env bash
# Renders the same views with two phyir binaries and compares every EXR they write, pixel for
# pixel: the check a refactoring commit runs to show its output did not change (or, for a
# deliberate re-baseline, by how much it did). Views: the generated mini and hard rooms of
# seeds 1-3, each as a 128x64 panorama at 16 spp with every AOV and a 16x32 grid of 8x16
# cache-mode probes, and as a 64x32 panorama with a 4x8 grid of path-mode probes.
#
# Usage: scripts/bit_identity.sh BEFORE_BINARY AFTER_BINARY [WORK_DIR]
#   Exits 0 when every file is bit-identical, 1 when any differs (each listed with its largest
#   difference and relative RMSE), 2 on bad arguments. About 2 minutes on 2 cores.
set -euo pipefail
if [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ] || [ $# -lt 2 ]; then
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'
  [ $# -lt 2 ] && [ "${1:-}" != "--help" ] && [ "${1:-}" != "-h" ] && exit 2
  exit 0
fi
before=$(realpath "$1")
after=$(realpath "$2")
work=${3:-$(mktemp -d)}
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
for b in "$before" "$after"; do [ -x "$b" ] || { echo "bit_identity: $b is not an executable" >&2; exit 2; }; done
mkdir -p "$work"

# The scenes come from the AFTER binary's generator, so both render the same files.
views=()
for preset in mini hard; do
  for seed in 1 2 3; do
    "$after" --log-level warn scenes generate --out "$work/scenes/$preset$seed" --count 1 --seed "$seed" --preset "$preset"
    views+=("$preset$seed")
  done
done

render_all() {  # binary, output folder
  local n=0
  for view in "${views[@]}"; do
    n=$((n + 1))
    echo "bit_identity: $(basename "$2"): view $n/${#views[@]} ($view)"
    local scene="$work/scenes/$view/room_0.gltf" seed=${view: -1}
    "$1" --log-level warn render "$scene" --out "$2/$view" --width 128 --height 64 --spp 16 --seed "$seed" \
      --probes --probe-grid 16x32 --probe-res 8x16
    "$1" --log-level warn render "$scene" --out "$2/${view}_path" --width 64 --height 32 --spp 4 --seed "$seed" \
      --probes --probe-grid 4x8 --probe-res 8x16 --probe-mode path --probe-spp 4
  done
}
render_all "$before" "$work/before"
render_all "$after" "$work/after"
/usr/bin/python3 "$root/scripts/compare_exr.py" "$work/before" "$work/after"
