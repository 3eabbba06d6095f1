#!/usr/bin/env bash
# `phyir dataset generate` survives kill -9: a tiny dataset (2 mini rooms x 3 views) is
# killed twice while views are being rendered (once a view is complete and another is half
# written), then the same command is run again. Checks: no manifest.json while incomplete
# (and verify refuses it); the re-run finishes with no interrupted writes left; verify
# passes; every file and the manifest are byte-identical to an uninterrupted run (timing.json,
# the one wall-clock file, excepted); views completed before a kill were not rendered again
# (same inode and mtime, and the log says so). Then a damaged file: verify names it and
# exits 1; a re-run renders only that view again and the dataset is whole and identical.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"

"$phyir" --log-level warn scenes generate --out rooms --count 2 --seed 1 --preset mini
args=(dataset generate --scenes rooms --preset tiny --views-per-scene 3 --threads 2 --quiet)

"$phyir" --log-level warn "${args[@]}" --out ref
[ -f ref/manifest.json ] || die "uninterrupted run wrote no manifest.json"

complete_views() { { find run/views -mindepth 2 -maxdepth 2 -type d -name 'v[0-9]*' 2>/dev/null || true; } | wc -l; }
partial_views() { { find run/views -mindepth 2 -maxdepth 2 -type d -name '.tmp-*' 2>/dev/null || true; } | wc -l; }

# Two kills, each once one more view is complete and another one is being written.
for round in 1 2; do
  before=$(complete_views)
  "$phyir" --log-level warn "${args[@]}" --out run > "kill$round.log" 2>&1 &
  pid=$!
  killed=0
  for _ in $(seq 1 1500); do
    if [ "$(complete_views)" -gt "$before" ] && [ "$(partial_views)" -gt 0 ]; then
      kill -9 "$pid" 2>/dev/null && killed=1
      break
    fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.01
  done
  wait "$pid" 2>/dev/null || true
  [ "$killed" = 1 ] || die "round $round: the run ended before it could be killed mid-view (see kill$round.log)"
  [ -f run/manifest.json ] && die "round $round: manifest.json exists although views are missing"
  echo "round $round: killed with $(complete_views) complete view(s) and $(partial_views) half-written"
done
n_done=$(complete_views)
[ "$n_done" -ge 2 ] && [ "$n_done" -lt 6 ] || die "expected 2-5 complete views after the kills, found $n_done"
if "$phyir" --log-level warn dataset verify run > verify_incomplete.log 2>&1; then
  die "verify accepted an unfinished dataset"
fi
grep -q "has not finished" verify_incomplete.log || die "verify did not say the run is unfinished: $(cat verify_incomplete.log)"

# Stamps (inode, mtime in ns) of the complete views and their files.
stamps() { find run/views -mindepth 3 -maxdepth 3 -type f ! -name timing.json -path "$1" -printf '%p %i %T@\n' | sort; }
for d in run/views/*/v[0-9]*; do stamps "$d/*"; done > stamps_before.txt

"$phyir" "${args[@]}" --out run > resume.log 2>&1 || { cat resume.log; die "re-run failed"; }
grep -q "$n_done of 6 views of shard 0/1 already complete" resume.log || die "re-run did not report $n_done kept views: $(cat resume.log)"
rendered=$(grep -c "dataset: room_.* done in" resume.log || true)
[ "$rendered" -eq $((6 - n_done)) ] || die "re-run rendered $rendered views, expected $((6 - n_done))"
while read -r path inode mtime; do
  now=$(stat -c '%i' "$path")" "$(find "$path" -printf '%T@')
  [ "$now" = "$inode $mtime" ] || die "$path was written again by the re-run"
done < stamps_before.txt

"$phyir" --log-level warn dataset verify run > verify.log || { cat verify.log; die "verify failed after resume"; }
find run -name '.tmp-*' -o -name '*.partial-*' | grep -q . && die "interrupted writes left behind"
diff -r -x timing.json ref run > diff.log || { head -20 diff.log; die "resumed dataset differs from the uninterrupted run"; }
cmp ref/manifest.json run/manifest.json || die "manifests differ"

# A damaged file: verify names it; a re-run repairs only that view.
victim=run/views/room_1/v002/depth.exr
truncate -s 100 "$victim"
if "$phyir" --log-level warn dataset verify run > verify_bad.log 2>&1; then die "verify missed a truncated file"; fi
grep -q "views/room_1/v002/depth.exr" verify_bad.log || die "verify did not name the damaged file: $(cat verify_bad.log)"
"$phyir" "${args[@]}" --out run > repair.log 2>&1 || { cat repair.log; die "repair run failed"; }
grep -q "room_1/v002: rendering it again" repair.log || die "repair run did not re-render the damaged view"
[ "$(grep -c "dataset: room_.* done in" repair.log)" -eq 1 ] || die "repair run rendered more than the damaged view"
"$phyir" --log-level warn dataset verify run > /dev/null || die "verify failed after repair"
diff -r -x timing.json ref run > /dev/null || die "repaired dataset differs from the uninterrupted run"
echo "dataset_resume_test: OK ($n_done of 6 views survived two kill -9, the rest rendered on resume)"
