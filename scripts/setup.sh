#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a working toolkit: installs the Debian
# packages (as root or via sudo), builds, then runs the main job on a small built-in
# example: a procedural `mini` room, rendered as a 360-degree HDR panorama with AOVs.
# Outputs land in example/ (override with PHYIR_EXAMPLE_DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
phyir="${PHYIR_BUILD_DIR:-$root/build}/cli/phyir"
out="${PHYIR_EXAMPLE_DIR:-$root/example}"
"$phyir" --version
"$phyir" scenes generate --out "$out/rooms" --count 1 --seed 1 --preset mini
"$phyir" scenes info "$out/rooms/room_0.gltf"
"$phyir" render "$out/rooms/room_0.gltf" --out "$out/render" --width 512 --height 256 --spp 64 --seed 1
echo
echo "setup: done. The example room is $out/rooms/room_0.gltf; its panorama and labels are in $out/render/"
ls -l "$out/render"
