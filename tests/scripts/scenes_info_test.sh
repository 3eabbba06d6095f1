#!/usr/bin/env bash
# `phyir scenes info` end to end: --json on every Khronos sample reports the README's
# reference counts; the text form names the file; a broken file exits 1 with the problem
# on stderr and nothing on stdout.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail

phyir=$1
work=$2
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
shared=${PHYIR_SHARED_DIR:-$root/../shared}
khronos=$shared/testdata/khronos
rm -rf "$work"
mkdir -p "$work"

die() { echo "FAIL: $*" >&2; exit 1; }

# file, mesh instances, triangles, materials, textures, cameras (README "Reference counts").
while read -r file instances triangles materials textures cameras; do
  "$phyir" --log-level error scenes info --json "$khronos/$file" > "$work/$file.json" \
    || die "scenes info failed on $file"
  /usr/bin/python3 - "$work/$file.json" "$instances" "$triangles" "$materials" "$textures" "$cameras" <<'PY' \
    || die "counts of $file differ from the README"
import json, sys
info = json.load(open(sys.argv[1]))
s = info["source_info"]
got = [s["mesh_instances"], info["triangles"], s["materials"], s["textures"], s["cameras"]]
want = [int(v) for v in sys.argv[2:]]
if got != want:
    sys.exit(f"{sys.argv[1]}: got {got}, want {want}")
PY
done <<'TABLE'
Triangle.gltf 1 1 0 0 0
TriangleWithoutIndices.gltf 1 1 0 0 0
SimpleSparseAccessor.gltf 1 12 0 0 0
SimpleMeshes.gltf 2 2 0 0 0
Cameras.gltf 1 2 0 0 2
MultipleScenes.gltf 1 2 0 0 0
BoxVertexColors.gltf 1 12 0 0 0
BoxTextured.gltf 1 12 1 1 0
TextureCoordinateTest.gltf 5 10 5 1 0
OrientationTest.gltf 13 524 7 0 0
TABLE

"$phyir" scenes info "$khronos/BoxTextured.gltf" > "$work/text.txt" || die "text output failed"
grep -q "scene: .*BoxTextured.gltf" "$work/text.txt" || die "text output does not name the file"
grep -q "geometry: 1 meshes, 12 triangles" "$work/text.txt" || die "text output lacks the geometry line"

bad=$root/tests/data/gltf/missing_bin.gltf
status=0
"$phyir" scenes info --json "$bad" > "$work/bad.out" 2> "$work/bad.err" || status=$?
[ "$status" -eq 1 ] || die "a missing .bin gave exit status $status, expected 1"
grep -q "buffer 0 uri 'missing.bin' not found" "$work/bad.err" || die "stderr does not name the missing .bin"
[ ! -s "$work/bad.out" ] || die "a failed load printed to stdout"
echo "scenes_info_test: ok"
