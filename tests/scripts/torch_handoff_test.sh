#!/usr/bin/env bash
# `phyir` does not load LibTorch; the network's commands (train, infer, bench model, eval
# --model) run in phyir-torch beside it, with the same arguments (cli/torch_handoff.h).
# Without the network built (PHYIR_BUILD_MODEL=OFF) they exit 3 and say so.
#   $1 = phyir binary, $2 = scratch folder (emptied).
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"

# Outputs go to files before grep -q: with pipefail, a writer cut off by grep's early exit
# (SIGPIPE) would fail the pipeline.
ldd "$phyir" > phyir.ldd
! grep -q "libtorch" phyir.ldd || die "phyir links LibTorch: $(grep libtorch phyir.ldd)"
"$phyir" --help > help.log
for command in train infer; do grep -qE "^ +$command " help.log || die "phyir --help does not list $command"; done

torch_cli=$(dirname "$phyir")/phyir-torch
if [ ! -x "$torch_cli" ]; then
  "$phyir" train --help > train_help.log
  grep -q "not built: PHYIR_BUILD_MODEL=OFF" train_help.log || die "train --help without the network does not say so"
  rc=0
  "$phyir" infer --model x.pt > off.log 2>&1 || rc=$?
  [ "$rc" -eq 3 ] && grep -q "PHYIR_BUILD_MODEL=OFF" off.log || die "infer without the network: exit $rc, $(cat off.log)"
  echo "torch hand-off: phyir built without the network; its commands say so"
  exit 0
fi
ldd "$torch_cli" > torch_cli.ldd
grep -q "libtorch" torch_cli.ldd || die "phyir-torch does not link LibTorch"

# The full help of each command comes from phyir-torch, global options first or not.
"$phyir" train --help > train_help.log
grep -q -- "--stage" train_help.log || die "phyir train --help is not the network's"
"$phyir" --log-level warn infer --help > infer_help.log
grep -q -- "--input" infer_help.log || die "phyir --log-level warn infer --help is not the network's"
"$phyir" bench model --help > bench_model_help.log
grep -q -- "--settings" bench_model_help.log || die "phyir bench model --help is not the network's"
# Errors are phyir-torch's, and its exit status is phyir's.
rc=0
"$phyir" infer --model missing.pt --input missing.png --out out > infer.log 2>&1 || rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "missing.pt" infer.log || die "infer with a missing checkpoint: exit $rc, $(cat infer.log)"
# eval --model's hand-off runs in eval_regression_test.
echo "torch hand-off: phyir is torch-free, train, infer and bench model run in phyir-torch"
