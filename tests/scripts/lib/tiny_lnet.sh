# Sourced after prologue.sh by the scripts that need a network's `phyir infer` output: exits 0
# (skipped) when phyir was built without the model, else makes, in the working directory, a
# generated mini room (rooms/), a one-view tiny dataset of it (data/) and an LNet trained for
# one step on it (lnet/checkpoint.pt). Its weights do not matter, only that its outputs are
# the toolkit's.
export OMP_WAIT_POLICY=passive
if "$phyir" train --help 2>&1 | grep -q "not built"; then
  echo "SKIP: phyir built without the model (-DPHYIR_BUILD_MODEL=OFF)"; exit 0
fi
"$phyir" --log-level warn scenes generate --out rooms --count 1 --seed 7 --preset mini
"$phyir" --log-level warn dataset generate --scenes rooms --out data --preset tiny --views-per-scene 1 \
  --split 1,0,0 --seed 1 --threads 2 --quiet
tiny_net=(--seed 1 --threads 1 --quiet --input-height 32 --input-width 64 --render-height 16 --render-width 32
          --probe-height 4 --probe-width 8 --diffuse-samples 8 --specular-samples 4 --width-divisor 4)
"$phyir" --log-level warn train --data data --out lnet --stage lnet --epochs 1 --batch 1 "${tiny_net[@]}"
