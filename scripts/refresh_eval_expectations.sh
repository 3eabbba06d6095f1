#!/usr/bin/env bash
# Rewrites tests/data/eval/expected_metrics.json from a fresh run of the eval regression
# pipeline (tests/scripts/eval_regression_test.sh with PHYIR_EVAL_REFRESH set) on the stored
# dataset: run it after a deliberate change of the metrics or the network, and commit the new
# file with the change that explains it. Tolerances and must_beat are kept. With --dataset it
# first renders the stored dataset (tests/data/eval/tiny_dataset.tar.xz) again: after a change
# of the dataset's format or content. The run pins every processor-dependent kernel
# (tests/scripts/pinned_kernels.sh), so the expectations hold on any x86-64 processor,
# whichever one refreshes them (the dataset is stored because renders are not: docs/eval.md).
#   scripts/refresh_eval_expectations.sh [--dataset] [PHYIR_BINARY] [SCRATCH_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mode=1
if [ "${1:-}" = --dataset ]; then mode=dataset; shift; fi
case "${1:-}" in -h|--help) sed -n '2,10p' "$0"; exit 0 ;; esac
phyir=${1:-$root/build/cli/phyir}
work=${2:-$(mktemp -d)}
PHYIR_EVAL_REFRESH=$mode PHYIR_SOURCE_ROOT=$root bash "$root/tests/scripts/eval_regression_test.sh" "$phyir" "$work"
git -C "$root" diff --stat -- tests/data/eval/ || true
