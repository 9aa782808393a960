#!/usr/bin/env bash
# pelage as a C++ user meets it (README, "Using pelage from C++"): installs BUILD_DIR into a fresh
# prefix, checks what a consumer needs is there (CLI, libraries, headers, CMake package, data, the
# Python package) and the version everywhere, then configures examples/ as a separate CMake
# project with find_package(pelage), builds it and runs the tutorials (the fourth, a window, under
# Xvfb when it is there). Run by CTest as `install_package` (make test).
#   scripts/install-test.sh BUILD_DIR VERSION
set -euo pipefail
if [ $# -ne 2 ] || [ ! -d "$1" ]; then
  echo "usage: scripts/install-test.sh BUILD_DIR VERSION" >&2
  exit 2
fi
build=$(cd "$1" && pwd)
version=$2
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() {
  echo "install-test: FAILED: $*" >&2
  exit 1
}
say() { echo "install-test: $*"; }

cmake --install "$build" --prefix "$prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }

# 1. What a consumer needs, where the package says it is.
for f in bin/pelage include/pelage/scene/model.h include/pelage/util/version.h \
  share/pelage/presets/default.json share/pelage/models/monkey.json; do
  [ -f "$prefix/$f" ] || fail "$f is not installed"
done
config=$(find "$prefix" -name pelageConfig.cmake)
[ -n "$config" ] || fail "no pelageConfig.cmake"
for f in pelageConfigVersion.cmake pelageTargets.cmake; do
  [ -f "$(dirname "$config")/$f" ] || fail "no $f beside $config"
done
for m in util anatomy skin fur models animation gltf scene render viewer; do
  [ -n "$(find "$prefix" -name "libpelage_$m.a")" ] || fail "libpelage_$m.a is not installed"
  grep -q "pelage::$m " "$(dirname "$config")/pelageTargets.cmake" || fail "pelage::$m is not exported"
done
say "prefix holds the CLI, $(find "$prefix/include" -name '*.h' | wc -l) headers, the libraries and the package"

# 2. One version: CMake's project(VERSION), the CLI, the Python package.
[ "$("$prefix/bin/pelage" --version)" = "pelage $version" ] ||
  fail "pelage --version says '$("$prefix/bin/pelage" --version)', CMake's project says $version"
site=$(find "$prefix" -type d -name site-packages | head -1)
if [ -n "$site" ] && [ -d "$site/pelage" ]; then
  pyversion=$(cd "$work" && PYTHONPATH="$site" /usr/bin/python3 -c 'import pelage; print(pelage.__version__)')
  [ "$pyversion" = "$version" ] || fail "pelage.__version__ is '$pyversion', CMake's project says $version"
fi
say "version $version (pelage --version, pelage.__version__)"

# 3. Installed headers make sense from outside: no src/ path, every pelage include installed.
while IFS= read -r h; do
  if grep -qE '#include +["<][^">]*src/' "$h"; then fail "$h includes a src/ path"; fi
  for inc in $(grep -oE '#include +"pelage/[^"]+"' "$h" | sed -E 's/.*"(.*)"/\1/'); do
    [ -f "$prefix/include/$inc" ] || fail "$h includes $inc, which is not installed"
  done
done < <(find "$prefix/include" -name '*.h')
say "every installed header includes only installed headers"

# 4. The tutorials as a separate project, against the prefix only.
cmake -S "$src/examples" -B "$work/examples" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON >"$work/configure.log" ||
  { cat "$work/configure.log"; fail "configuring examples/ with find_package(pelage)"; }
found=$(sed -n 's/^pelage_DIR:PATH=//p' "$work/examples/CMakeCache.txt")
[ "$found" = "$(dirname "$config")" ] || fail "find_package(pelage) found '$found', not the prefix"
cmake --build "$work/examples" -j 2 >"$work/build.log" || { cat "$work/build.log"; fail "building examples/"; }
say "examples/ configured with find_package(pelage) from $found and built"

ex=$work/examples
model=monkey
[ -f "$src/../shared/models/Fox/Fox.glb" ] && model=$src/../shared/models/Fox/Fox.glb
mkdir -p "$work/out" "$work/tree"
"$ex/101_hair_ply" "$model" "" 2 "$work/out" >"$work/101.log" || { cat "$work/101.log"; fail "101_hair_ply"; }
for f in 0 1; do
  ply=$work/out/hairs_0000$f.ply
  [ -f "$ply" ] || fail "101_hair_ply wrote no $ply"
  head -c 300 "$ply" | grep -aqE '^element vertex [1-9]' || fail "$ply has no vertices"
done
# The installed libraries give the same hairs as the tree's.
if [ -x "$build/bin/101_hair_ply" ]; then
  "$build/bin/101_hair_ply" "$model" "" 2 "$work/tree" >/dev/null
  cmp -s "$work/out/hairs_00001.ply" "$work/tree/hairs_00001.ply" ||
    fail "the installed 101_hair_ply's hairs differ from the tree's"
fi
say "101_hair_ply: $(head -1 "$work/101.log")"

"$ex/102_droop" 31 >"$work/102.log" || { cat "$work/102.log"; fail "102_droop"; }
[ "$(grep -cE '^ +[0-9]+ ' "$work/102.log")" -eq 31 ] || { cat "$work/102.log"; fail "102_droop printed no 31 frames"; }
awk 'NR > 1 && ($3 <= 0 || $3 >= 180) { exit 1 }' "$work/102.log" || fail "102_droop: droop out of (0, 180) degrees"
say "102_droop: 31 frames, last: $(tail -1 "$work/102.log" | tr -s ' ')"

"$ex/103_render_png" monkey "$work/out/frame.png" 320 180 >"$work/103.log" ||
  { cat "$work/103.log"; fail "103_render_png"; }
size=$(od -An -tu1 -j16 -N8 "$work/out/frame.png" | awk '{print $3 * 256 + $4 "x" $7 * 256 + $8}')
[ "$size" = "320x180" ] || fail "103_render_png wrote a $size PNG, not 320x180"
say "103_render_png: $(cat "$work/103.log")"
# The fourth needs a display: under Xvfb when there is one (CI has it), two frames.
if command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 1280x720x24" "$ex/104_gl_loop" monkey 2 >"$work/104.log" 2>&1 ||
    { cat "$work/104.log"; fail "104_gl_loop under Xvfb"; }
  say "104_gl_loop (Xvfb, 2 frames): $(tail -1 "$work/104.log")"
fi
say "passed"
