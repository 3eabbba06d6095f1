#!/usr/bin/env bash
# `phyir assets list` and `phyir assets info` on the fixture library (tests/data/assets):
# --help of both, the licence and category lines, --category filtering, one entry in full with
# its normalised bounds and materials, and the failures (unknown category, unknown id, a folder
# without libraries, a broken archive) exiting 1 with one line naming the problem.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"
assets=$root/tests/data/assets/fixture

"$phyir" assets list --help > help.txt
grep -q -- "--category" help.txt || die "list --help does not list --category"
grep -q "sweethome3d-furniture" help.txt || die "list --help does not name the Debian package"
"$phyir" assets info --help | grep -q -- "--assets" || die "info --help does not list --assets"

"$phyir" assets list --assets "$assets" > list.txt
cat list.txt
grep -qF "# PhyIR fixture (5 entries, PhyirFixture.sh3f): Public domain (CC0 1.0)" list.txt || die "no library line"
grep -qF "PhyIR#lamp | Lights | Lamp | 0.300 x 0.600 x 0.300 | Fixture Maker | light x2" list.txt || die "no lamp line"
grep -qF "PhyIR#window | Doors and windows | Double casement window | 1.000 x 1.200 x 0.100 | Fixture Maker | window fixed" list.txt \
  || die "no window line"
grep -qF "# categories: Doors and windows 1; Kitchen 1; Lights 1; Living room 1; Miscellaneous 1; total 5" list.txt \
  || die "no category counts"

"$phyir" assets list --assets "$assets" --category Kitchen > kitchen.txt
[ "$(grep -vc '^#' kitchen.txt)" = 1 ] || die "--category Kitchen should list one entry"
grep -q "^PhyIR#table | Kitchen" kitchen.txt || die "--category Kitchen lists no table"

"$phyir" assets info "PhyIR#chair" --assets "$assets" > chair.txt
cat chair.txt
grep -qF "bounds: (-0.230, 0.000, -0.250) .. (0.230, 0.925, 0.250)" chair.txt || die "chair bounds are not its catalog box"
grep -qF "material 1 'steel': base (0.319, 0.319, 0.319) roughness 0.300 metallic 1.00" chair.txt || die "no steel material"
"$phyir" assets info "PhyIR#lamp" --assets "$assets" | grep -qF "light source at (-0.050, 0.400, -0.050) m" \
  || die "lamp light source misplaced"

expect_failure() {  # expect_failure "message part" command...
  local part=$1; shift
  if "$@" > out.txt 2> err.txt; then die "'$*' should fail"; fi
  [ "$(wc -l < err.txt)" = 1 ] || { cat err.txt; die "'$*' should print one line"; }
  grep -qF -- "$part" err.txt || { cat err.txt; die "'$*' does not say '$part'"; }
}
expect_failure "no category 'Sofas' (categories: Doors and windows, Kitchen" "$phyir" assets list --assets "$assets" --category Sofas
expect_failure "no furniture with the id 'PhyIR#sofa'" "$phyir" assets info "PhyIR#sofa" --assets "$assets"
expect_failure "$root/tests/data: no .sh3f furniture library in this folder" "$phyir" assets list --assets "$root/tests/data"
expect_failure "bad_number.sh3f: width#2=abc is not a number (line 16)" \
  "$phyir" assets list --assets "$root/tests/data/assets/broken/bad_number.sh3f"
expect_failure "m/lines.obj (entry 'Broken#lines'): no triangles" \
  "$phyir" assets info "Broken#lines" --assets "$root/tests/data/assets/broken/broken_models.sh3f"
echo "assets_cli_test: ok"
