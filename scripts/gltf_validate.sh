#!/usr/bin/env bash
# Validates glTF files with the Khronos glTF-Validator and prints error/warning/info counts.
#   scripts/gltf_validate.sh [--fail-on-warnings] [--quiet] FILE.gltf...
# Exit status: 0 = no errors, 1 = errors (or warnings with --fail-on-warnings), 2 = setup or
# usage problem. Needs node and npm (Debian: nodejs npm). The validator, npm package
# gltf-validator, is installed on first use into $PHYIR_NPM_CACHE (default
# ~/.cache/phyir-npm; a folder under $TMPDIR when $HOME is not writable).
set -euo pipefail

VALIDATOR_VERSION=2.0.0-dev.3.10  # pinned: new validator releases add checks
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)

if [ $# -eq 0 ]; then
  sed -n '2,7p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
  exit 2
fi
. "$here/npm_package.sh"
prefix=$(npm_package gltf_validate gltf-validator "$VALIDATOR_VERSION")

NODE_PATH="$prefix/node_modules" exec node "$here/gltf_validate.js" "$@"
