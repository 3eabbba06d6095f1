#!/usr/bin/env bash
# Builds the toolkit with AddressSanitizer + UndefinedBehaviorSanitizer in its own folder
# (build-asan) and runs the test suite there; any sanitizer report fails the run.
# Called by .ci/run after scripts/test.sh; docs/robustness.md (measured time, what it covers).
#
# Left out, for the CI time budget (this script took 26 min from a cold folder on the 2-core
# VM, of CI's 90 for all three scripts; docs/robustness.md): the LibTorch network and its tests
# (PHYIR_BUILD_MODEL=OFF: torch headers alone take ~30 s per file to compile, and an ASan
# LibTorch run of the training tests takes far longer than the budget) and the
# micro-benchmarks (PHYIR_BUILD_BENCH=OFF: speed, not correctness). Everything else (core,
# scenes, render, dataset, cli, with the unit and script tests) builds and runs under the
# sanitizers, except the tests excluded below and the long statistical tests that skip
# themselves (tests/sanitizer_skip.h), each with its reason. The test files are compiled
# without instrumentation (PHYIR_SANITIZE, tests/CMakeLists.txt). ccache
# (CMAKE_CXX_COMPILER_LAUNCHER, as scripts/build.sh) makes rebuilds cheap.
#
# Usage: scripts/sanitize.sh   (PHYIR_ASAN_BUILD_DIR, PHYIR_JOBS override the defaults)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PHYIR_ASAN_BUILD_DIR:-$root/build-asan}"
jobs="${PHYIR_JOBS:-$(nproc)}"
start=$(date +%s)

# clang, at -O1 (the level the sanitizers' documentation recommends): GCC 12 took twice as
# long to compile a file with ASan + UBSan, and -O2 another half again. PHYIR_BUILD_FUZZ: the
# glTF loader's fuzz target is built here too, for scripts/fuzz.sh (core/ and scenes/ get
# libFuzzer's coverage instrumentation; the sanitizer runtime serves its callbacks in tests).
command -v clang++ >/dev/null || { echo "sanitize: clang++ not found (scripts/install_deps.sh installs clang)" >&2; exit 1; }
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DPHYIR_SANITIZE=ON -DPHYIR_BUILD_FUZZ=ON -DPHYIR_BUILD_MODEL=OFF -DPHYIR_BUILD_BENCH=OFF -DPHYIR_BUILD_TESTS=ON >/dev/null
cmake --build "$build" -j "$jobs"
built=$(date +%s)

# halt_on_error: the first report ends the test with a failure. Leak checking stays on; the
# few leaks inside system libraries we cannot fix are listed in scripts/lsan.supp.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=0:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"

# Tests that cannot run under ASan, and why:
#  - slurm_dataset_test: it installs (apt-get) and starts system daemons (munged, slurmctld,
#    slurmd) and has them run phyir as batch jobs: a test of the cluster set-up, not of our
#    code under the sanitizers, and a second cluster start in one CI run only costs time.
#    What it exercises of ours (sharding, merge, verify) runs here in dataset_shards_test
#    and the dataset_test suite.
#  - slurm_train_test: the same daemons, for training, which is not built here.
exclude='^(slurm_dataset_test|slurm_train_test)$'

cd "$build"
ctest --output-on-failure -j "$jobs" --timeout 1500 -E "$exclude"
end=$(date +%s)
echo "sanitize: build $((built - start)) s, tests $((end - built)) s, total $((end - start)) s"
