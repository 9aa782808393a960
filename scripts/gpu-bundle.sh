#!/usr/bin/env bash
# Builds a self-contained `pelage` for a Linux machine with an NVIDIA GPU and none of pelage's
# packages installed (such as the device machine described in ../shared/docs/headless-gl.md):
# DIST/pelage plus every shared library it loads, in DIST/lib (libglvnd's libEGL, libOpenGL and
# libGLdispatch included; the NVIDIA driver's own EGL vendor library is found there at run time).
# The binary finds DIST/lib through a DT_RPATH of $ORIGIN/lib (--disable-new-dtags: a DT_RUNPATH
# would not cover libEGL's own dependency on libGLdispatch). glibc is not bundled; a Debian 12
# build (glibc 2.36) runs on newer glibc.
#
# Usage: scripts/gpu-bundle.sh [BUILD_DIR (default build-gpu)] [DIST (default dist)]
# Then, on the GPU machine, from the repository root:
#   dist/pelage view --benchmark    (the monkey: 500k, 1M, 5M polyline hairs at 1920x1080)
# If EGL finds no NVIDIA device there, point glvnd at the driver's vendor file, e.g.
#   __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
# (the first line printed names the renderer: it must not be llvmpipe).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-gpu}
dist=${2:-dist}

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPELAGE_WERROR=ON \
  -DPELAGE_BUILD_TESTS=OFF -DPELAGE_BUILD_BENCH=OFF "${launcher[@]}" \
  -DCMAKE_EXE_LINKER_FLAGS=-Wl,--disable-new-dtags '-DCMAKE_BUILD_RPATH=$ORIGIN/lib' >/dev/null
cmake --build "$build" --target pelage

rm -rf "$dist"
mkdir -p "$dist/lib"
cp "$build/bin/pelage" "$dist/pelage"
if ! readelf -d "$dist/pelage" | grep -q 'RPATH.*\$ORIGIN/lib'; then
  echo "gpu-bundle: $dist/pelage has no DT_RPATH \$ORIGIN/lib" >&2
  exit 1
fi
# Every library the binary loads, except glibc's own (the target's must be used).
ldd "$dist/pelage" | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so.* | libm.so.* | libdl.so.* | libpthread.so.* | librt.so.* | ld-linux*) ;;
    *) cp -L "$lib" "$dist/lib/" ;;
  esac
done
echo "gpu-bundle: $dist/pelage and $(ls "$dist/lib" | wc -l) libraries in $dist/lib ($(du -sh "$dist" | cut -f1))"
