#!/usr/bin/env bash
# Runs the test suite once per instruction-set level this processor supports, with every
# library that picks kernels by the processor capped at that level: how one machine runs
# the code paths of older processors (issue: a suite that passes on any x86-64 machine).
#   scripts/test_isa_levels.sh [LEVEL...] [-- CTEST_ARGS...]
# Levels: sse4 (SSE4.1/4.2, x86-64-v2), avx2 (x86-64-v3), avx512 (x86-64-v4, uncapped);
# default: every level the processor has. The build must exist (scripts/build.sh).
# Prints one line per level: its caps, the ctest verdict and the failing tests.
set -uo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${PHYIR_BUILD_DIR:-$root/build}"
levels=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do levels+=("$1"); shift; done
[ "${1:-}" = -- ] && shift
flags=$(grep -m1 '^flags' /proc/cpuinfo)
if [ ${#levels[@]} -eq 0 ]; then
  grep -qw sse4_2 <<<"$flags" && levels+=(sse4)
  grep -qw avx2 <<<"$flags" && levels+=(avx2)
  grep -qw avx512f <<<"$flags" && levels+=(avx512)
fi

# The caps of one level, as environment assignments (oneDNN, ATen and SLEEF, glibc's libm,
# Embree).
caps() {
  case "$1" in
    sse4) sed -n 's/^export //p' "$root/tests/scripts/pinned_kernels.sh" | tr '\n' ' ' ;;  # the tests' own pin
    avx2) echo "DNNL_MAX_CPU_ISA=AVX2 ATEN_CPU_CAPABILITY=avx2 GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX512F PHYIR_EMBREE_MAX_ISA=avx2" ;;
    avx512) echo "" ;;
    *) echo "test_isa_levels: unknown level '$1' (sse4, avx2, avx512)" >&2; exit 2 ;;
  esac
}

status=0
cd "$build" || { echo "test_isa_levels: no build in $build (scripts/build.sh)" >&2; exit 2; }
for level in "${levels[@]}"; do
  assignments=$(caps "$level") || exit 2
  log="$build/test_isa_$level.log"
  start=$(date +%s)
  env $assignments ctest --output-on-failure -j "${PHYIR_JOBS:-$(nproc)}" --timeout 1200 "$@" > "$log" 2>&1
  rc=$?
  summary=$(grep -E "tests passed|tests failed" "$log" | tail -1)
  failed=$(sed -n '/The following tests FAILED/,$p' "$log" | grep -E '^\s+[0-9]+ -' | sed 's/^\s*//' | tr '\n' ';')
  echo "$level [${assignments:-uncapped}]: ${summary:-no summary} ($(( $(date +%s) - start )) s) ${failed}"
  [ $rc -eq 0 ] || status=1
done
exit $status
