#!/usr/bin/env bash
# A figure of `phyir bench insert` composites beside the truth (docs/insert.md): for each
# PLACEMENT/OBJECT given, a row of crops round the object, enlarged 6x with a box filter (the
# pixels stay visible): the truth, then one composite per lighting, each labelled.
#
#   scripts/insert_figure.sh BENCH_DIR OUT.png "gt predicted global constant" PLACEMENT/OBJECT...
#
# Crops are 48 x 32 pixels centred on the object's mask (seed 1), clamped to the image.
set -euo pipefail
[ $# -ge 4 ] || { sed -n 2,8p "$0"; exit 2; }
bench=$1; out=$2; read -r -a lightings <<< "$3"; shift 3
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
# A font for the labels (OIIO has none of its own); without one the tiles go unlabelled.
font=$(ls /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf \
          /usr/share/matplotlib/mpl-data/fonts/ttf/DejaVuSans.ttf 2>/dev/null | head -1 || true)
tiles=()
for case in "$@"; do
  dir="$bench/$case/seed_1"
  [ -f "$dir/truth.png" ] || { echo "insert_figure: $dir/truth.png missing" >&2; exit 1; }
  read -r x y < <(/usr/bin/python3 - "$dir/${lightings[0]}/mask.png" <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio
m = oiio.ImageBuf(sys.argv[1]).get_pixels(oiio.FLOAT)[..., 0] > 0.5
ys, xs = np.nonzero(m)
h, w = m.shape
cx, cy = int(xs.mean()), int(ys.mean())
print(min(max(cx - 24, 0), w - 48), min(max(cy - 16, 0), h - 32))
PY
)
  for name in truth "${lightings[@]}"; do
    src="$dir/$name/composite.png"; [ "$name" = truth ] && src="$dir/truth.png"
    [ -f "$src" ] || { echo "insert_figure: $src missing" >&2; exit 1; }
    tile="$tmp/${#tiles[@]}.png"
    label=(); [ -n "$font" ] && label=(--text:x=4:y=16:size=14:color=1,1,0:font="$font" "$name")
    oiiotool "$src" --cut "48x32+$x+$y" --resize 288x192:filter=box --ch R,G,B "${label[@]}" -o "$tile"
    tiles+=("$tile")
  done
done
oiiotool "${tiles[@]}" --mosaic:pad=2 "$(( ${#lightings[@]} + 1 ))x$#" -o "$out"
echo "wrote $out"
