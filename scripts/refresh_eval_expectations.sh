#!/usr/bin/env bash
# Rewrites tests/data/eval/expected_metrics.json from a fresh run of the eval regression
# pipeline (tests/scripts/eval_regression_test.sh with PHYIR_EVAL_REFRESH set): run it after a
# deliberate change of the metrics, the renderer, the dataset or the network, and commit the
# new file with the change that explains it. Tolerances and must_beat are kept.
#   scripts/refresh_eval_expectations.sh [--this-cpu] [PHYIR_BINARY] [SCRATCH_DIR]
# Without --this-cpu the expectations become this CPU's alone (other CPUs' entries are stale
# after a change). With it, the code unchanged, this CPU's own entry is added beside the
# others' so that the test keeps its narrow tolerances here too (docs/eval.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
mode=1
if [ "${1:-}" = --this-cpu ]; then mode=cpu; shift; fi
phyir=${1:-$root/build/cli/phyir}
work=${2:-$(mktemp -d)}
PHYIR_EVAL_REFRESH=$mode PHYIR_SOURCE_ROOT=$root bash "$root/tests/scripts/eval_regression_test.sh" "$phyir" "$work"
git -C "$root" diff --stat -- tests/data/eval/expected_metrics.json || true
