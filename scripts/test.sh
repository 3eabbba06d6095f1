#!/usr/bin/env bash
# The test command (README, .ci/run): installs missing Debian packages, builds, and runs
# every GoogleTest suite and integration script through ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
cd "${PHYIR_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j "${PHYIR_JOBS:-$(nproc)}" --timeout 1200
