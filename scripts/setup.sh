#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a working toolkit: installs the Debian
# packages (as root or via sudo), builds, then runs the main job on a built-in example: a
# furnished three-room apartment from Debian's furniture library, its living room rendered
# by day as a 360-degree HDR panorama with its labels and a 32 x 64 grid of light probes
# (2-4 minutes on 2 cores), and one contact-sheet PNG of it all. Outputs land in
# example/ (override with PHYIR_EXAMPLE_DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
phyir="${PHYIR_BUILD_DIR:-$root/build}/cli/phyir"
out="${PHYIR_EXAMPLE_DIR:-$root/example}"
"$phyir" --version
"$phyir" scenes generate --out "$out/apartment" --count 1 --seed 1 --preset apartment --rooms 3 --lighting day
# To a file, then its head: piped into head, phyir would be cut off (SIGPIPE) and, with
# pipefail, end this script.
"$phyir" scenes info "$out/apartment/apartment_0.gltf" > "$out/scene_info.txt"
head -8 "$out/scene_info.txt"
# 512 samples per pixel: the sunlit room's indirect light is grainy at 64 (its walls and ceiling
# are lit by the sun patch on the floor, which no light sample finds); at 512 it is clean at a
# glance, for about 200 CPU seconds. color.png is auto-exposed (render.json records the stops).
"$phyir" render "$out/apartment/apartment_0.gltf" --out "$out/render" --width 512 --height 256 --spp 512 --seed 1 \
  --probes --probe-grid 32x64
/usr/bin/python3 "$root/scripts/apartments/contact_sheet.py" --out "$out/contact_sheet.png" --width 320 --probes 4 \
  "$out/render"
echo
echo "setup: done. The example apartment is $out/apartment/apartment_0.gltf; its panorama, labels and"
echo "probes are in $out/render/, and $out/contact_sheet.png shows them side by side."
ls -l "$out/render"
