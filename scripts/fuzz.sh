#!/usr/bin/env bash
# Fuzzes every input reader with libFuzzer under ASan + UBSan for a bounded time.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET=60] [TARGET...]
#        scripts/fuzz.sh ci      (CI: a fixed seed and a fixed number of runs per target, 25-40 s
#                                 each, one target per core, so a CI result is reproducible)
# Builds build-fuzz with clang (installs clang-14 and its runtime if missing), seeds each target's
# corpus with the project's files (fuzz/corpus/, models/) and the shared glTF models (and the images
# they carry), and runs each
# target for SECONDS. A crash, leak, sanitizer report or timeout leaves the input in
# build-fuzz/artifacts/<target>/ and makes the script fail: add that file to
# fuzz/regressions/<target>/ (tests/fuzz replays them in every build) and fix the bug.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
ci=0
if [ "$seconds" = ci ]; then ci=1; seconds=0; fi
# Runs per target in CI mode (about 25-40 s each at the rates measured on a 2-core VM; two thirds
# of the counts before the strokes target came, to keep CI under an hour).
declare -A ci_runs=([creature]=130000 [preset]=200000 [clip]=200000 [pose]=330000 [gltf]=3000 [mesh]=13000 [image]=2000 [groom]=60000 [strokes]=60000)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(creature preset clip pose gltf mesh image groom strokes)
build=build-fuzz

if ! command -v clang++-14 >/dev/null || ! ls /usr/lib/llvm-14/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  echo "fuzz: installing clang-14 and libclang-rt-14-dev"
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends clang-14 libclang-rt-14-dev >/dev/null
fi

CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPELAGE_FUZZ=ON -DPELAGE_SANITIZE=ON -DPELAGE_BUILD_VIEWER=OFF -DPELAGE_BUILD_TESTS=OFF \
  -DPELAGE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

shared=../shared/models
seed() {  # seed TARGET FILE...: copies existing files into the target's working corpus
  local dir="$build/corpus/$1"; shift
  for f in "$@"; do [ -f "$f" ] && cp "$f" "$dir/"; done
  return 0
}
# seed_gltf_images DIR MODEL...: the images the glTF models carry (glb buffer views, data URIs,
# files beside a .gltf), one file each, as texture seeds.
seed_gltf_images() {
  local dir="$1"; shift
  /usr/bin/python3 - "$dir" "$@" <<'PY' || true
import base64, json, os, struct, sys
out = sys.argv[1]
for path in sys.argv[2:]:
    if not os.path.isfile(path):
        continue
    data = open(path, "rb").read()
    binary = b""
    if data[:4] == b"glTF":
        n = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + n])
        if len(data) > 28 + n:
            binary = data[28 + n:]
    else:
        doc = json.loads(data)
    for k, image in enumerate(doc.get("images", [])):
        if "bufferView" in image:
            view = doc["bufferViews"][image["bufferView"]]
            start = view.get("byteOffset", 0)
            blob = binary[start:start + view["byteLength"]]
        elif image.get("uri", "").startswith("data:"):
            blob = base64.b64decode(image["uri"].split(",", 1)[1])
        else:
            file = os.path.join(os.path.dirname(path), image.get("uri", ""))
            blob = open(file, "rb").read() if os.path.isfile(file) else b""
        if blob:
            name = os.path.splitext(os.path.basename(path))[0]
            open(os.path.join(out, f"{name}_{k}"), "wb").write(blob)
PY
}
# fuzz_one TARGET: seeds the target's corpus and fuzzes it; its report goes to build/fuzz_T.report
# and its status to build/fuzz_T.status (0: no problem).
fuzz_one() {
  local t="$1" report="$build/fuzz_$1.report" status=0
  [ $ci -eq 1 ] && rm -rf "$build/corpus/$t"
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t"
  seed "$t" fuzz/corpus/"$t"/* fuzz/regressions/"$t"/*
  case "$t" in
    creature) seed "$t" models/*.json tests/scene/*.json ;;
    preset)   seed "$t" models/presets/*.json ;;
    gltf)     seed "$t" "$shared"/RiggedSimple/*.glb "$shared"/SimpleSkin/*.gltf "$shared"/RiggedFigure/*.glb \
                        "$shared"/Fox/*.glb ;;
    image)    seed_gltf_images "$build/corpus/$t" "$shared"/*/*.glb "$shared"/*/*.gltf ;;
  esac
  local budget
  if [ $ci -eq 1 ]; then
    budget=(-seed=1 -runs="${ci_runs[$t]}")
    echo "== fuzz_$t: ${ci_runs[$t]} runs (seed 1), $(ls "$build/corpus/$t" | wc -l) seed files" >"$report"
  else
    budget=(-max_total_time="$seconds")
    echo "== fuzz_$t: ${seconds}s, $(ls "$build/corpus/$t" | wc -l) seed files" >"$report"
  fi
  if ! ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      "$build/bin/fuzz_$t" "$build/corpus/$t" "${budget[@]}" -timeout=20 -rss_limit_mb=4096 \
      -max_len=1048576 -artifact_prefix="$build/artifacts/$t/" -print_final_stats=1 \
      >"$build/fuzz_$t.log" 2>&1; then
    status=1
    echo "fuzz_$t FOUND A PROBLEM (log: $build/fuzz_$t.log, input in $build/artifacts/$t/):" >>"$report"
    grep -E "ERROR|SUMMARY|runtime error|Test unit written" "$build/fuzz_$t.log" | head -8 >>"$report" || true
  fi
  { grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$build/fuzz_$t.log" | tr '\n' ' ' || true; echo; } >>"$report"
  echo "$status" >"$build/fuzz_$t.status"
}
# The targets run side by side, one per core (each is one single-threaded libFuzzer process; a
# fixed seed and run count give the same runs either way), their reports printed in order.
jobs_max=$(nproc 2>/dev/null || echo 2)
for t in "${targets[@]}"; do
  rm -f "$build/fuzz_$t.status"
  while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait
failed=()
for t in "${targets[@]}"; do
  cat "$build/fuzz_$t.report"
  [ "$(cat "$build/fuzz_$t.status" 2>/dev/null || echo 1)" = 0 ] || failed+=("$t")
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: problems found by: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: no problems found"
