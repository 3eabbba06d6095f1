#!/usr/bin/env bash
# Makes the @gltf-transform/cli variants of a glTF that exercise the loader's extensions:
#   scripts/gltf_variants.sh IN.gltf OUTDIR
# writes OUTDIR/{draco,meshopt,quantize,instance}.gltf, each with its own .bin (draco.bin, ...)
# and the input's textures beside them (the same PNGs, shared by the four variants):
#   draco     KHR_draco_mesh_compression (edgebreaker, default quantization bits)
#   meshopt   EXT_meshopt_compression, --level high: quantized first (KHR_mesh_quantization),
#             with meshopt's filters where they apply (octahedral for normals and tangents)
#   quantize  KHR_mesh_quantization (normalized integer positions, normals, tangents; the
#             dequantization goes into the nodes' scale and translation)
#   instance  EXT_mesh_gpu_instancing for every mesh used by 2 or more nodes (--min 2)
# Needs node (>= 20) and npm. The CLI, npm package @gltf-transform/cli, is installed on first
# use into $PHYIR_NPM_CACHE/@gltf-transform_cli (scripts/npm_package.sh; default ~/.cache/phyir-npm; a folder under
# $TMPDIR when $HOME is not writable). Exit status: 0 = written, 1 = a conversion failed,
# 2 = setup or usage problem.
set -euo pipefail

CLI_VERSION=4.5.1  # pinned: new releases change encoders and defaults
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

if [ $# -ne 2 ]; then
  sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
  exit 2
fi
in=$1 outdir=$2
[ -f "$in" ] || { echo "gltf_variants: input '$in' not found" >&2; exit 2; }
. "$here/npm_package.sh"
prefix=$(npm_package gltf_variants @gltf-transform/cli "$CLI_VERSION")
cli=$prefix/node_modules/.bin/gltf-transform

mkdir -p "$outdir"
# gltf-transform keeps the input's buffer URI (lit_room.bin for every variant), so each
# variant is written into a scratch folder first; its buffers are renamed after it (NAME.bin,
# NAME_1.bin, ...) and moved out with the textures.
scratch=$(mktemp -d "${TMPDIR:-/tmp}/gltf_variants.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
run() {  # NAME COMMAND [OPTIONS...]
  local name=$1 command=$2
  shift 2
  echo "gltf_variants: $name: gltf-transform $command $in $name.gltf $*" >&2
  rm -rf "${scratch:?}/$name" && mkdir "$scratch/$name"
  if ! "$cli" "$command" "$in" "$scratch/$name/$name.gltf" "$@" >"$scratch/$name.log" 2>&1; then
    cat "$scratch/$name.log" >&2
    echo "gltf_variants: gltf-transform $command failed on $in" >&2
    exit 1
  fi
  node -e '
    const fs = require("fs"), path = require("path");
    const [file, name] = process.argv.slice(1);
    const dir = path.dirname(file);
    const doc = JSON.parse(fs.readFileSync(file, "utf8"));
    let k = 0;
    for (const buffer of doc.buffers || []) {
      if (!buffer.uri || buffer.uri.startsWith("data:")) continue;
      const uri = k === 0 ? `${name}.bin` : `${name}_${k}.bin`;
      fs.renameSync(path.join(dir, decodeURIComponent(buffer.uri)), path.join(dir, uri + ".tmp"));
      buffer.uri = uri;
      k += 1;
    }
    for (const f of fs.readdirSync(dir)) if (f.endsWith(".bin.tmp")) fs.renameSync(path.join(dir, f), path.join(dir, f.slice(0, -4)));
    fs.writeFileSync(file, JSON.stringify(doc, null, 2) + "\n");
  ' "$scratch/$name/$name.gltf" "$name"
  mv -f "$scratch/$name"/* "$outdir/"
}
run draco draco --method edgebreaker
run meshopt meshopt --level high
run quantize quantize
run instance instance --min 2

# What each variant declares.
for name in draco meshopt quantize instance; do
  node -e '
    const doc = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
    const fmt = (a) => JSON.stringify(a || []);
    console.log(`${process.argv[2]}: extensionsUsed ${fmt(doc.extensionsUsed)} extensionsRequired ${fmt(doc.extensionsRequired)}`);
  ' "$outdir/$name.gltf" "$name"
done
