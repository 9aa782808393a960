#!/usr/bin/env bash
# The aarch64 build: the core libraries (util, anatomy, skin, models, fur; the fur kernel on
# Highway's NEON target) and their tests, cross-compiled with Debian's g++-aarch64-linux-gnu
# against the arm64 packages (multiarch), then every one of their tests run under qemu-user (the
# NEON kernel against the scalar reference, bit for bit). Installs what it needs (root or sudo). Usage: scripts/cross-aarch64.sh [build dir] (default build-aarch64).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build-aarch64}
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "cross-aarch64: need root or sudo to install packages" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
# (libgomp1:arm64: the tests run on the arm64 packages' own loader and C library, see below.)
packages=(g++-aarch64-linux-gnu qemu-user libhwy-dev:arm64 libopenmesh1:arm64 libgtest-dev:arm64
          libgmock-dev:arm64 libstb-dev:arm64 libgomp1:arm64 libeigen3-dev nlohmann-json3-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "cross-aarch64: installing ${missing[*]}"
  dpkg --print-foreign-architectures | grep -qx arm64 || $sudo dpkg --add-architecture arm64
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# libopenmesh-dev is not co-installable for two architectures (installing the arm64 one would
# remove the machine's own): its arm64 package is unpacked into the build folder instead.
openmesh="$BUILD/arm64-openmesh"
if [ ! -f "$openmesh/usr/lib/aarch64-linux-gnu/cmake/OpenMesh/OpenMeshConfig.cmake" ]; then
  mkdir -p "$openmesh"
  (cd "$openmesh" && apt-get download -qq libopenmesh-dev:arm64 libopenmesh1:arm64 2>/dev/null &&
    for d in ./*.deb; do dpkg-deb -x "$d" .; done && rm -f ./*.deb)
fi
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
  -DCMAKE_BUILD_TYPE=Release -DPELAGE_WERROR=ON -DPELAGE_CORE_ONLY=ON \
  -DOpenMesh_DIR="$PWD/$openmesh/usr/lib/aarch64-linux-gnu/cmake/OpenMesh" >/dev/null
cmake --build "$BUILD" -j "$(nproc)"  # (the core libraries and every core suite)
readelf -h "$BUILD/tests/fur_tests" | grep -q "AArch64" || { echo "cross-aarch64: not an aarch64 binary" >&2; exit 1; }
# Every core suite but the slow-labelled monkey ones (5 min under qemu) under qemu-user (cmake/aarch64-linux-gnu.cmake: the emulator, no -L): the
# binaries load /lib/ld-linux-aarch64.so.1 and the C library of the arm64 packages (libc6:arm64),
# as on an arm64 Debian machine. (With `-L /usr/aarch64-linux-gnu` the cross toolchain's loader,
# glibc 2.36-8cross1, met libc6:arm64's libc.so.6, 2.36-9+deb12u*: pthread_create then looped
# forever in the loader's stack cache, which stopped every test that starts threads.)
echo "cross-aarch64: the core suites under qemu-aarch64"
scripts/ctest.sh "$BUILD" -j "$(nproc)" --timeout 600 -LE slow
