#!/usr/bin/env bash
# Hostile input through the command line (issue 8; docs/robustness.md). Every case must end
# with a non-zero exit below 128 (no crash, no signal), a message naming the problem, and
# no output that looks complete (no render.json, no manifest.json). Cases:
#  1. every failing file of the hostile glTF corpus through `scenes info` and `render`;
#  2. bad command-line values (sizes, counts, positions, names, ranges);
#  3. output folders that cannot be written;
#  4. a dataset with corrupt, truncated, swapped or missing EXRs: `dataset verify` names them;
#  5. checkpoints that are not checkpoints or come from another configuration (when the
#     network is built): `train` and `infer` refuse them clearly.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
phyir=$1
work=$2
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
corpus=$root/tests/data/hostile
scene=$root/tests/data/gltf/textured_quad.gltf
rm -rf "$work"
mkdir -p "$work"
cd "$work"
die() { echo "FAIL: $*" >&2; exit 1; }
cases=0

# expect_failure NAME PHRASE CMD...: CMD exits non-zero (not by a signal) and its output
# contains PHRASE (a fixed string).
expect_failure() {
  local name=$1 phrase=$2
  shift 2
  local rc=0
  "$@" > "$name.log" 2>&1 || rc=$?
  [ "$rc" -ne 0 ] || die "$name: exit 0 (expected an error): $*"
  [ "$rc" -lt 128 ] || die "$name: killed by signal $((rc - 128)) (a crash): $*: $(tail -5 "$name.log")"
  [ "$rc" -ne 2 ] || [ -n "${allow_internal:-}" ] || ! grep -q "internal error" "$name.log" ||
    die "$name: internal error instead of a clear message: $(cat "$name.log")"
  grep -qF -- "$phrase" "$name.log" || die "$name: message lacks '$phrase': $(cat "$name.log")"
  cases=$((cases + 1))
}

# --- 1. the hostile glTF corpus --------------------------------------------------------------
failing=$(cd "$corpus" && python3 -c 'import json; d = json.load(open("expected.json"))["files"]; print("\n".join(sorted(k for k, v in d.items() if v != ["__loads__"])))')
n_corpus=0
[ -z "${PHYIR_HOSTILE_SKIP_CORPUS:-}" ] || failing=""  # quick iterations on the other parts
for name in $failing; do
  expect_failure "info_$name" "$name:" "$phyir" scenes info "$corpus/$name"
  expect_failure "render_$name" "$name:" "$phyir" render "$corpus/$name" --out "out_$name" --width 8 --height 4 --spp 1 --quiet
  [ ! -e "out_$name/render.json" ] || die "render of $name left a render.json behind"
  n_corpus=$((n_corpus + 1))
done
echo "hostile corpus: $n_corpus files refused by scenes info and render"

# --- 2. bad command-line values ---------------------------------------------------------------
# A valid render of the test scene (it has no camera node: the position is given).
r() { echo render "$scene" --quiet --spp 1 --width 8 --height 4 "$@"; }
bad_render() {  # NAME PHRASE ARGS...: render with ARGS appended must fail, leaving no render.json
  local name=$1 phrase=$2
  shift 2
  local camera=(--camera 0,0.5,1)
  case "$*" in *--camera*) camera=() ;; esac
  expect_failure "$name" "$phrase" "$phyir" $(r --out "out_$name") "${camera[@]}" "$@"
  [ ! -e "out_$name/render.json" ] || die "$name left a render.json behind"
}
"$phyir" $(r --out out_valid --camera 0,0.5,1) > valid.log 2>&1 || die "the valid render the cases start from fails: $(cat valid.log)"
[ -f out_valid/render.json ] || die "the valid render wrote no render.json"
bad_render width_zero "--width" --width 0
bad_render width_negative "--width" --width -5
bad_render width_text "--width" --width abc
bad_render spp_zero "--spp" --spp 0
bad_render camera_two_numbers "--camera '1,2'" --camera 1,2
bad_render camera_text "--camera" --camera a,b,c
bad_render projection_unknown "unknown projection 'fisheye'" --projection fisheye
bad_render camera_index "camera" --camera-index 99
bad_render environment_missing "missing.exr" --environment missing.exr
bad_render view_unknown "Bogus" --view Bogus
bad_render probe_grid_zero "--probe-grid" --probes --probe-grid 0x4
bad_render probe_res_malformed "--probe-res" --probes --probe-res 16by32
bad_render probe_offset_zero "--probe-offset" --probes --probe-offset 0
bad_render probe_mode_unknown "probe" --probes --probe-mode magic
expect_failure scene_missing "no_such_scene.gltf" "$phyir" render no_such_scene.gltf --out out_missing
expect_failure scenes_generate_count "--count" "$phyir" scenes generate --out rooms_bad --count -1
expect_failure scenes_generate_preset "preset" "$phyir" scenes generate --out rooms_bad --count 1 --preset enormous
expect_failure unknown_command "'nonsense' is not a command" "$phyir" nonsense
echo "bad command-line values: refused"

# --- 3. output folders that cannot be written ---------------------------------------------------
# Checked before any work (ensure_writable_directory): a clear message naming the folder,
# exit 1, nothing rendered.
echo "a file, not a folder" > plain_file
expect_failure out_under_a_file "plain_file" "$phyir" $(r --out plain_file/out --camera 0,0.5,1)
[ ! -e plain_file/out ] || die "render created something under a regular file"
expect_failure out_is_a_file "plain_file" "$phyir" $(r --out plain_file --camera 0,0.5,1)
grep -q "a file, not a folder" plain_file || die "render overwrote a regular file given as --out"
expect_failure out_in_proc "/proc/phyir_out" "$phyir" $(r --out /proc/phyir_out --camera 0,0.5,1)
expect_failure generate_out_under_a_file "plain_file" "$phyir" scenes generate --out plain_file/rooms --count 1 --preset mini
echo "unwritable output folders: refused"

# --- 4. a damaged dataset ---------------------------------------------------------------------
"$phyir" --log-level warn scenes generate --out rooms --count 1 --seed 3 --preset mini > /dev/null
"$phyir" --log-level warn dataset generate --scenes rooms --out ds --preset tiny --views-per-scene 1 --threads 2 --quiet > ds.log 2>&1 \
  || { cat ds.log; die "could not generate the test dataset"; }
"$phyir" --log-level warn dataset verify ds > /dev/null || die "the fresh dataset does not verify"
view=$(cd ds && find views -mindepth 2 -maxdepth 2 -type d | head -1)
damaged() {  # NAME PHRASE DAMAGE-COMMAND...: copy ds, damage it, verify must fail naming PHRASE
  local name=$1 phrase=$2
  shift 2
  rm -rf "ds_$name"
  cp -r ds "ds_$name"
  (cd "ds_$name" && "$@")
  expect_failure "verify_$name" "$phrase" "$phyir" --log-level warn dataset verify "ds_$name"
}
flip_middle() {  # overwrite 64 bytes in the middle of a file with 0xff
  local size
  size=$(stat -c %s "$1")
  printf '\377%.0s' $(seq 64) | dd of="$1" bs=1 seek=$((size / 2)) conv=notrunc status=none
}
damaged exr_bytes_flipped "$view/color.exr" flip_middle "$view/color.exr"
damaged exr_zero_bytes "$view/normal.exr" truncate -s 0 "$view/normal.exr"
damaged exr_header_only "$view/depth.exr" truncate -s 40 "$view/depth.exr"
damaged exr_is_a_png "$view/roughness.exr" cp "$view/input.png" "$view/roughness.exr"
damaged exr_missing "$view/metalness.exr" rm "$view/metalness.exr"
damaged exr_swapped "$view/basecolor.exr" cp "$view/depth.exr" "$view/basecolor.exr"
damaged manifest_truncated "manifest.json" truncate -s 100 manifest.json
damaged manifest_not_json "manifest.json" sh -c 'echo "not json {" > manifest.json'
echo "damaged dataset: verify names every damaged file"

# --- 5. checkpoints ---------------------------------------------------------------------------
"$phyir" train --help > train_help.log 2>&1 || true
if ! grep -q "PHYIR_BUILD_MODEL=OFF" train_help.log; then
  net=(--input-height 32 --input-width 64 --render-height 16 --render-width 32 --width-divisor 4
       --diffuse-samples 4 --specular-samples 4 --threads 1 --batch 1 --max-steps 1 --epochs 1)
  "$phyir" --log-level warn train --data ds --split "" --out ck --stage gmnet "${net[@]}" > ck.log 2>&1 \
    || { cat ck.log; die "tiny training run failed"; }
  [ -f ck/checkpoint.pt ] || die "tiny training wrote no checkpoint"
  head -c 5000 /dev/urandom > random.pt
  expect_failure infer_random_checkpoint "random.pt" "$phyir" infer --model random.pt --input "ds/$view/input.png" --out inf1
  cp "$root/tests/data/gltf/textured_quad.gltf" not_a_checkpoint.pt
  expect_failure infer_text_checkpoint "not_a_checkpoint.pt" "$phyir" infer --model not_a_checkpoint.pt --input "ds/$view/input.png" --out inf2
  head -c 3000 ck/checkpoint.pt > truncated.pt
  expect_failure infer_truncated_checkpoint "truncated.pt" "$phyir" infer --model truncated.pt --input "ds/$view/input.png" --out inf3
  for d in inf1 inf2 inf3; do [ ! -e "$d/infer.json" ] || die "$d: infer.json written from a bad checkpoint"; done
  # Another configuration: a gmnet checkpoint resumed as the lnet stage.
  mkdir -p ck_other && cp ck/checkpoint.pt ck_other/
  expect_failure resume_other_stage "gmnet" "$phyir" train --data ds --split "" --out ck_other --stage lnet --resume "${net[@]}"
  expect_failure init_random "random.pt" "$phyir" train --data ds --split "" --out ck_bad --stage lnet --init random.pt "${net[@]}"
  echo "bad checkpoints: refused"
else
  echo "checkpoints: skipped (phyir built without the network, PHYIR_BUILD_MODEL=OFF)"
fi

echo "hostile_cli_test: OK ($cases cases)"
