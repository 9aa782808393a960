#!/bin/bash
# A pelage frame next to its path-traced reference (Blender Cycles), measured.
#
# usage: scripts/reference-render.sh MODEL OUTDIR [pelage render options...]
#   e.g. scripts/reference-render.sh monkey out/ref --clip walk --frames 10 --size 960x720 \
#          --camera three-quarter
#
# 1. pelage renders the frame as users do (OUTDIR/pelage/frame_NNNNN.png, transparent background);
# 2. pelage renders it again with every hair (--no-culling, CPU hairs) and writes that frame as a
#    reference scene (OUTDIR/scene/frame_NNNNN.pelscene: camera, light, skin, hairs);
# 3. Blender Cycles path-traces the scene twice with different seeds, SAMPLES / 2 samples each
#    (scripts/reference/cycles_render.py; OUTDIR/cycles_a.png, OUTDIR/cycles_b.png);
# 4. scripts/reference/compare.py writes their mean (OUTDIR/cycles.png), OUTDIR/figures.json (the
#    reference's detail without its own noise, measured from the two renders' difference) and
#    OUTDIR/side_by_side.png (pelage | Cycles | |difference| x 4), over pelage's default background.
# Give one frame (--frames N). SAMPLES (default 256, at least 2) sets Cycles' samples per pixel in
# all. PASSES=1 also writes the first render's light passes into OUTDIR/passes/
# (cycles_render.py --passes). Blender is installed here only (apt-get install blender, as
# root), never by make test.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
model=$1 out=$2
shift 2
pelage=${PELAGE:-build/bin/pelage}
samples=${SAMPLES:-256}
[ -x "$pelage" ] || { echo "reference-render: $pelage is not built (make build)" >&2; exit 2; }
case "$samples" in
  '' | *[!0-9]* | 0 | 1) echo "reference-render: SAMPLES=$samples is not a count of at least 2" >&2; exit 2 ;;
esac
if ! command -v blender > /dev/null; then
  if [ "$(id -u)" = 0 ] && command -v apt-get > /dev/null; then
    echo "reference-render: installing Blender (Debian's; a few minutes)"
    apt-get install -y --no-install-recommends blender > /dev/null
  else
    echo "reference-render: needs Blender 3.4 (Debian: apt-get install blender)" >&2
    exit 2
  fi
fi
mkdir -p "$out"
rm -rf "$out/pelage" "$out/scene" "$out/passes" "$out"/cycles*.png
"$pelage" render "$model" --out "$out/pelage" --background transparent --quiet "$@"
"$pelage" render "$model" --out "$out/scene" --background transparent --quiet --no-culling \
  --hair-source cpu --scene-files "$@"
scenes=("$out"/scene/*.pelscene)
frames=("$out"/pelage/frame_*.png)
if [ ${#scenes[@]} -ne 1 ] || [ ${#frames[@]} -ne 1 ]; then
  echo "reference-render: give one frame (--frames N); got ${#frames[@]}" >&2
  exit 2
fi
blender -b --factory-startup -noaudio --python-exit-code 1 --python scripts/reference/cycles_render.py -- \
  "${scenes[0]}" "$out/cycles_a.png" "$out/cycles_b.png" --samples $((samples / 2)) \
  ${PASSES:+--passes "$out/passes"} > "$out/blender.log" 2>&1 ||
  { tail -20 "$out/blender.log" >&2; echo "reference-render: Blender failed" >&2; exit 1; }
grep -E "^cycles_render" "$out/blender.log" || true
[ -s "$out/cycles_a.png" ] && [ -s "$out/cycles_b.png" ] ||
  { echo "reference-render: Blender wrote no image" >&2; exit 1; }
/usr/bin/python3 scripts/reference/compare.py "${frames[0]}" "$out/cycles_a.png" "$out/cycles_b.png" \
  --background 0.80 0.82 0.86 --json "$out/figures.json" --side-by-side "$out/side_by_side.png" \
  --reference-mean "$out/cycles.png"
