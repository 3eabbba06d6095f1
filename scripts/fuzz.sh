#!/usr/bin/env bash
# Builds the libFuzzer target for the glTF/GLB loader with clang (AddressSanitizer and
# UndefinedBehaviorSanitizer on, coverage instrumentation of core/ and scenes/), in
# scripts/sanitize.sh's folder when that has built it (build-asan) or else in its own
# (build-fuzz), and runs it for a bounded time on a copy of the checked-in seed corpus
# (fuzz/corpus), with a glTF dictionary. Exits non-zero on any finding: a crash, a sanitizer
# report, an exception other than phyir::Error, a single malloc above the RSS limit (an
# unbounded allocation) or an input slower than the per-input timeout (a hang). The crashing
# input is left in findings/ of that folder, for `gltf_loader_fuzz FILE` to reproduce.
# Called by .ci/run after scripts/sanitize.sh; docs/robustness.md.
#
# Usage: scripts/fuzz.sh [seconds]   (default 60; PHYIR_FUZZ_BUILD_DIR, PHYIR_JOBS override)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
asan_build="${PHYIR_ASAN_BUILD_DIR:-$root/build-asan}"
build="${PHYIR_FUZZ_BUILD_DIR:-}"
jobs="${PHYIR_JOBS:-$(nproc)}"
seconds="${1:-60}"
start=$(date +%s)

command -v clang++ >/dev/null || { echo "fuzz: clang++ not found (scripts/install_deps.sh installs clang)" >&2; exit 1; }
# scripts/sanitize.sh builds the fuzz target with everything else (same compiler, level and
# sanitizers): after it, as in .ci/run, its folder is used and nothing is compiled again.
# Otherwise a folder of its own with only core/ and scenes/: no tests, benchmarks or network.
if [ -z "$build" ] && grep -q "^PHYIR_BUILD_FUZZ:BOOL=ON" "$asan_build/CMakeCache.txt" 2>/dev/null; then
  build="$asan_build"
else
  build="${build:-$root/build-fuzz}"
  # ccache applies as in scripts/build.sh (CMAKE_CXX_COMPILER_LAUNCHER); -O1 as in sanitize.sh.
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_COMPILER=clang++ \
    -DPHYIR_BUILD_FUZZ=ON -DPHYIR_BUILD_TESTS=OFF -DPHYIR_BUILD_BENCH=OFF -DPHYIR_BUILD_MODEL=OFF >/dev/null
fi
cmake --build "$build" -j "$jobs" --target gltf_loader_fuzz
built=$(date +%s)

# A fresh working corpus each run, seeded from the checked-in one (the run adds to it).
work="$build/corpus"
findings="$build/findings"
rm -rf "$work" "$findings"
mkdir -p "$work" "$findings"
cp "$root"/fuzz/corpus/* "$work/"

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# -rss_limit_mb / -malloc_limit_mb: a file of a few KB must not make the loader allocate GBs.
# -timeout: no input may take longer than 10 s (a hang).
rc=0
"$build/fuzz/gltf_loader_fuzz" "$work" -dict="$root/fuzz/gltf.dict" -max_total_time="$seconds" \
  -max_len=16384 -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -print_final_stats=1 \
  -artifact_prefix="$findings/" 2>"$build/fuzz.log" || rc=$?
end=$(date +%s)
grep -E "stat::number_of_executed_runs|stat::peak_rss_mb|cov:" "$build/fuzz.log" | tail -4 || true
if [ "$rc" -ne 0 ]; then
  tail -60 "$build/fuzz.log" >&2
  echo "fuzz: FAILED (exit $rc); reproduce with: $build/fuzz/gltf_loader_fuzz $findings/<file>" >&2
  exit 1
fi
echo "fuzz: OK, $(ls "$work" | wc -l) inputs in the corpus; build $((built - start)) s, fuzzing $((end - built)) s, total $((end - start)) s"
