#!/usr/bin/env bash
# Installs the Debian 12 packages pelage needs. Idempotent: quiet and fast when all are present.
# Usage: scripts/install-deps.sh            (build + test + headless render)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libopenmesh-dev libeigen3-dev nlohmann-json3-dev libtinygltf-dev libcli11-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev libhwy-dev
  libglfw3-dev libimgui-dev
  libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  xvfb xauth ffmpeg
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pil
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "pelage: installing missing Debian packages: ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "pelage: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
