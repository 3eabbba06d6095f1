#!/usr/bin/env bash
# Installs every Debian 12 package the toolkit needs, only those missing. Safe to run twice.
# Needs root (or sudo) for apt-get.
set -euo pipefail

PACKAGES=(
  cmake ninja-build g++ ccache pkg-config git
  libembree-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libglm-dev
  libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev opencolorio-tools
  libtbb-dev libtorch-dev libgloo-dev libfmt-dev libspdlog-dev libcli11-dev libdraco-dev libmeshoptimizer-dev
  libtinyobjloader-dev libzip-dev sweethome3d-furniture
  libgtest-dev libgmock-dev libbenchmark-dev libssl-dev
  python3-numpy python3-matplotlib python3-openimageio python3-skimage
  clang libfuzzer-14-dev universal-ctags
)
# Node.js and npm run the Khronos glTF validator. Machines that already have them from
# elsewhere (e.g. a newer Node.js) keep theirs: Debian's npm would conflict with it.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  PACKAGES+=(nodejs npm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
