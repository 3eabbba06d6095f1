#!/usr/bin/env bash
# `phyir dataset generate --shard i/N` + `phyir dataset merge`: a tiny dataset (2 mini rooms x
# 3 views, 6 views: shard 0/2 holds room_0's, 1/2 room_1's; 0/4..3/4 cut scenes in the
# middle) rendered as 2 and as 4 shards (with other thread counts) merges into exactly the
# bytes of the unsharded run (manifest included; timing.json, the wall-clock file, excepted);
# verify passes on the merged folder; merge refuses a missing shard, a repeated shard, a shard
# with other settings and one of another partition, with a message naming the problem, and
# writes no manifest then.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"

"$phyir" --log-level warn scenes generate --out rooms --count 2 --seed 4 --preset mini
args=(--log-level warn dataset generate --scenes rooms --preset tiny --views-per-scene 3 --quiet)

"$phyir" "${args[@]}" --out whole --threads 2
for i in 0 1; do "$phyir" "${args[@]}" --out "s2_$i" --shard "$i/2" --threads 1; done
for i in 0 1 2 3; do "$phyir" "${args[@]}" --out "s4_$i" --shard "$i/4" --threads 2 --views-in-flight 1; done

views_in() { /usr/bin/python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))["views"]))' "$1/manifest.json"; }
[ "$(views_in s2_0)" = 3 ] && [ "$(views_in s2_1)" = 3 ] || die "2 shards should hold 3 views each"
total=0
for i in 0 1 2 3; do total=$((total + $(views_in "s4_$i"))); done
[ "$total" = 6 ] || die "4 shards hold $total views, expected 6"

"$phyir" --log-level warn dataset merge merged2 s2_1 s2_0
"$phyir" --log-level warn dataset merge merged4 s4_0 s4_1 s4_2 s4_3
for m in merged2 merged4; do
  diff -r -x timing.json whole "$m" > "$m.diff" || { head -20 "$m.diff"; die "$m differs from the unsharded run"; }
  cmp whole/manifest.json "$m/manifest.json" || die "$m/manifest.json differs"
  "$phyir" --log-level warn dataset verify "$m" > "$m.verify" || { cat "$m.verify"; die "verify failed on $m"; }
done

expect_refusal() {  # name, expected message, merge arguments...
  local name=$1 message=$2
  shift 2
  if "$phyir" dataset merge "refused_$name" "$@" > "refused_$name.log" 2>&1; then die "merge accepted $name"; fi
  grep -q "$message" "refused_$name.log" || die "merge ($name) did not say '$message': $(cat "refused_$name.log")"
  [ ! -e "refused_$name/manifest.json" ] || die "merge ($name) wrote a manifest"
}
expect_refusal missing "3 of 6 views are in no shard given" s2_0
expect_refusal repeated "are both shard 0/2" s2_0 s2_0
# A shard made with other settings (its manifest edited: rendering one costs time; the
# GoogleTest suite covers more refusals).
cp -r s2_1 s2_1_spp8
/usr/bin/python3 - s2_1_spp8/manifest.json <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["settings"]["render"]["spp"] = 8
json.dump(m, open(sys.argv[1], "w"))
PY
expect_refusal settings "different settings (settings.render.spp: 4 vs 8)" s2_0 s2_1_spp8
expect_refusal partitions "is shard 0/2 but s4_1 is shard 1/4" s2_0 s4_1
echo "dataset_shards_test: OK (2 and 4 shards merge into the unsharded bytes; inconsistent shards refused)"
