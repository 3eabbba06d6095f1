#!/usr/bin/env bash
# Regenerates the compressed and quantized variants in this folder (README.md lists them).
# Needs node/npm and a phyir binary (for the room). From the repository root:
#   npm install --prefix /tmp/gt @gltf-transform/cli@4.5.1
#   tests/data/gltf/compressed/make_variants.sh /tmp/gt build/cli/phyir
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
gt="$(cd "${1:?npm prefix holding @gltf-transform/cli}" && pwd)"
phyir="$(realpath "${2:?phyir binary}")"
G="$gt/node_modules/.bin/gltf-transform"
export NODE_PATH="$gt/node_modules"  # for the two .cjs helpers
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$here"

# The variants every model gets: IN NAME.
variants() {
  "$G" draco "$1" "$2_draco.glb"
  "$G" meshopt --level medium "$1" "$2_meshopt.glb"  # no filters
  "$G" quantize "$1" "$2_quantized.glb"              # 14-bit positions, 10-bit normals, 12-bit UVs
  node unnormalize.cjs "$2_quantized.glb" "$2_quantized_unnormalized.glb"
}

# The room (mini preset, seed 1) without textures, with xatlas UVs on every mesh (in
# [0, 1], which gltf-transform needs to quantize them) and MikkTSpace tangents.
"$phyir" scenes generate --out "$work/room" --seed 1 >/dev/null
node prepare_room.cjs "$work/room/room_0.gltf" "$work/room_prepared.glb"
"$G" unwrap "$work/room_prepared.glb" "$work/room_unwrapped.glb" --overwrite
"$G" tangents "$work/room_unwrapped.glb" room.glb
variants room.glb room
variants ../textured_quad.gltf quad

"$G" draco --method sequential room.glb room_draco_sequential.glb
# --level high filters normals and tangents (OCTAHEDRAL, 8-bit); the quad has neither. As
# .gltf + .bin: a fallback buffer without uri, which tinygltf alone refuses in a .gltf.
"$G" meshopt --level high room.glb room_meshopt_filters.gltf
"$G" quantize --quantize-position 8 --quantize-normal 8 --quantize-texcoord 8 room.glb room_quantized_8bit.glb
node unnormalize.cjs room_quantized_8bit.glb room_quantized_8bit_unnormalized.glb
