#!/usr/bin/env bash
# Installs the Debian 12 packages mane needs, only those that are missing, and any packages
# named as arguments (scripts/test.sh adds what only the tests use).
# Idempotent: a second run installs nothing. Runs as root, or through sudo otherwise.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git ca-certificates
  libglm-dev
  libvulkan-dev vulkan-tools mesa-vulkan-drivers vulkan-validationlayers
  glslang-tools glslang-dev spirv-tools
  libglfw3-dev xvfb xauth
  libosd-dev libmeshoptimizer-dev
  libopenexr-dev libtinygltf-dev libtinyobjloader-dev libstb-dev nlohmann-json3-dev libcli11-dev libssl-dev libcurl4-openssl-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev libbullet-dev
  python3-dev pybind11-dev python3-numpy python3-pytest
  curl
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  as_root=(sudo)
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
