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
for tool in node npm; do
  command -v "$tool" >/dev/null || { echo "gltf_validate: '$tool' not found (apt-get install nodejs npm)" >&2; exit 2; }
done

cache=${PHYIR_NPM_CACHE:-${HOME:-/nonexistent}/.cache/phyir-npm}
if ! mkdir -p "$cache" 2>/dev/null || [ ! -w "$cache" ]; then
  cache=${TMPDIR:-/tmp}/phyir-npm-$(id -u)
  mkdir -p "$cache"
fi
installed=$(node -p "try { require('$cache/node_modules/gltf-validator/package.json').version } catch (e) { '' }")
if [ "$installed" != "$VALIDATOR_VERSION" ]; then
  echo "gltf_validate: installing gltf-validator@$VALIDATOR_VERSION into $cache" >&2
  # Install beside the cache and move it in whole, so a concurrent or interrupted run never
  # sees half a package.
  staging=$(mktemp -d "$cache.staging.XXXXXX")
  trap 'rm -rf "$staging"' EXIT
  if ! npm install --silent --no-audit --no-fund --prefix "$staging" "gltf-validator@$VALIDATOR_VERSION" >&2; then
    echo "gltf_validate: npm install gltf-validator@$VALIDATOR_VERSION failed (no network or registry?)" >&2
    exit 2
  fi
  rm -rf "$cache/node_modules.old"
  [ -d "$cache/node_modules" ] && mv "$cache/node_modules" "$cache/node_modules.old"
  mv "$staging/node_modules" "$cache/node_modules"
  rm -rf "$cache/node_modules.old" "$staging"
  trap - EXIT
fi

NODE_PATH="$cache/node_modules" exec node "$here/gltf_validate.js" "$@"
