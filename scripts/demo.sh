#!/usr/bin/env bash
# `make demo`: the main job on the built-in monkey. Prints its summary, writes its posed skin, then
# renders its walk clip with fur offscreen (EGL: llvmpipe on a CPU machine, the GPU where there is
# one) to out/frames/frame_NNNNN.png and out/demo.mp4 (the render about seven minutes on 2 cores
# with llvmpipe: 395 s for the 60 frames, 2026-12-07).
set -euo pipefail
build=${1:-build}
bin=$build/bin/pelage
mkdir -p out
"$bin" info
"$bin" skin --out out/monkey_skin.obj
echo "demo: wrote out/monkey_skin.obj"
# Two walk cycles at 30 frames/s, seen from the side, the camera moving with the monkey, in the
# default coat (95 % of the skin hidden: about 830,000 hairs).
rm -rf out/frames
"$bin" render monkey --clip walk --frames 0:59 --fps 30 --size 640x360 --camera side --track \
  --out out/frames --video out/demo.mp4
echo "demo: wrote out/frames/frame_00000.png .. frame_00059.png and out/demo.mp4"
