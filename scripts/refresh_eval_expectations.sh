#!/usr/bin/env bash
# Rewrites tests/data/eval/expected_metrics.json from a fresh run of the eval regression
# pipeline (tests/scripts/eval_regression_test.sh with PHYIR_EVAL_REFRESH set): run it after a
# deliberate change of the metrics, the renderer, the dataset or the network, and commit the
# new file with the change that explains it. Tolerances and must_beat are kept. The run pins
# every processor-dependent kernel (tests/scripts/pinned_kernels.sh), so the expectations
# hold on any x86-64 processor, whichever one refreshes them.
#   scripts/refresh_eval_expectations.sh [PHYIR_BINARY] [SCRATCH_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
phyir=${1:-$root/build/cli/phyir}
work=${2:-$(mktemp -d)}
PHYIR_EVAL_REFRESH=1 PHYIR_SOURCE_ROOT=$root bash "$root/tests/scripts/eval_regression_test.sh" "$phyir" "$work"
git -C "$root" diff --stat -- tests/data/eval/expected_metrics.json || true
