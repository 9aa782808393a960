#!/usr/bin/env bash
# The README's NVIDIA figures, in one run on a GPU machine, from dist/ as scripts/gpu-bundle.sh
# builds it. Writes each step's output to OUT (default gpu-figures/) and prints it.
#   1. view --benchmark: the monkey's walk, 500k, 1M and 5M polyline hairs at 1920x1080, MSAA off
#      and 4x (end to end per frame: skinning, skin upload, GPU fur, drawing, glFinish);
#   2. render: 60 frames of the walk at 1920x1080, 500,000 polylines, culling off, PNGs written
#      (export frames/s), and the default look (strands, transparency, self-shadowing);
#   3. bench: CPU hairs of one frame, 500,000 hairs, all cores (hairs/s, ms/frame);
#   4. the demo's frame at 1920x1080 with the default fur (a look at the GPU's image);
#   5. frizz: the face with and without, and the demo's 60 frames with 2 mm.
# Usage (device machine, repository root): scripts/gpu-figures.sh [OUT]
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-gpu-figures}
mkdir -p "$out"
bin=dist/pelage
step() {
  local name=$1
  shift
  echo "== $name: $*" | tee -a "$out/figures.txt"
  local t0=$(date +%s%N)
  "$@" >"$out/$name.log" 2>&1
  local rc=$?
  local t1=$(date +%s%N)
  tail -n 25 "$out/$name.log" | tee -a "$out/figures.txt"
  echo "-- $name: exit $rc, $(((t1 - t0) / 1000000)) ms" | tee -a "$out/figures.txt"
}
{
  nvidia-smi -L 2>/dev/null
  lscpu | grep -E 'Model name|^CPU\(s\)'
} | tee "$out/figures.txt"
step view_benchmark "$bin" view --headless --benchmark --benchmark-frames 20
tmp=$(mktemp -d)
step render_lines "$bin" render --frames 0:59 --size 1920x1080 --hairs 500000 --no-culling \
  --lines --self-shadowing off --transparency off --out "$tmp/lines"
step render_default_500k "$bin" render --frames 0:59 --size 1920x1080 --hairs 500000 \
  --no-culling --out "$tmp/strands"
step render_demo_1080p "$bin" render --frames 0:59 --size 1920x1080 --out "$tmp/demo"
cp "$tmp/demo/frame_00020.png" "$out/demo_1080p_frame20.png" 2>/dev/null
step bench_cpu_500k "$bin" bench --hairs 500000 --repeat 30
# 5. frizz (README: Frizz) on the GPU: the monkey's face with and without 2 mm, transparent
#    background (scripts/fine-detail.py measures the fringe), and its cost over 60 frames.
for a in 0 2; do
  step "render_face_frizz$a" "$bin" render --frames 0 --size 960x540 --camera face \
    --background transparent --fur-set "overcoat.frizz.amplitude=$a" --out "$tmp/face$a"
  cp "$tmp/face$a/frame_00000.png" "$out/face_frizz$a.png" 2>/dev/null
done
step render_demo_1080p_frizz "$bin" render --frames 0:59 --size 1920x1080 \
  --fur-set overcoat.frizz.amplitude=2 --out "$tmp/frizz"
rm -rf "$tmp"
