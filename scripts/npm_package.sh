# Sourced by the scripts that run an npm tool (gltf_validate.sh, gltf_variants.sh): installs a
# pinned npm package on first use into its own prefix under $PHYIR_NPM_CACHE (default
# ~/.cache/phyir-npm; a folder under $TMPDIR when $HOME is not writable).
#   prefix=$(npm_package CALLER PACKAGE VERSION)   # then $prefix/node_modules/...
# Exits 2 with a message naming CALLER when node or npm is missing or the install fails.

npm_package() {
  local caller=$1 package=$2 version=$3 tool cache prefix installed staging
  for tool in node npm; do
    command -v "$tool" >/dev/null || { echo "$caller: '$tool' not found (apt-get install nodejs npm)" >&2; exit 2; }
  done
  cache=${PHYIR_NPM_CACHE:-${HOME:-/nonexistent}/.cache/phyir-npm}
  if ! mkdir -p "$cache" 2>/dev/null || [ ! -w "$cache" ]; then
    cache=${TMPDIR:-/tmp}/phyir-npm-$(id -u)
    mkdir -p "$cache"
  fi
  prefix=$cache/${package//\//_}
  installed=$(node -p "try { require('$prefix/node_modules/$package/package.json').version } catch (e) { '' }")
  if [ "$installed" != "$version" ]; then
    echo "$caller: installing $package@$version into $prefix" >&2
    # Install beside the cache and move it in whole, so a concurrent or interrupted run never
    # sees half a package.
    staging=$(mktemp -d "$prefix.staging.XXXXXX")
    if ! npm install --silent --no-audit --no-fund --prefix "$staging" "$package@$version" >&2; then
      rm -rf "$staging"
      echo "$caller: npm install $package@$version failed (no network or registry?)" >&2
      exit 2
    fi
    rm -rf "$prefix.old"
    [ -d "$prefix" ] && mv "$prefix" "$prefix.old"
    mv "$staging" "$prefix"
    rm -rf "$prefix.old"
  fi
  echo "$prefix"
}
