#!/usr/bin/env bash
# One render-farm task: renders its share of the frames FIRST..LAST with `pelage render --resume`.
# The task's index and the number of tasks come from the engine:
#   Slurm job array:         SLURM_ARRAY_TASK_ID (minus SLURM_ARRAY_TASK_MIN), SLURM_ARRAY_TASK_COUNT
#   Kubernetes Indexed Job:  JOB_COMPLETION_INDEX, and PELAGE_TASK_COUNT (= the Job's completions)
#   anything else:           PELAGE_TASK_INDEX, PELAGE_TASK_COUNT
# Settings (environment): PELAGE (the binary, default `pelage` on PATH), FIRST, LAST (inclusive
# frame numbers), OUT (the shared output directory), and PELAGE_ARGS (everything else given to
# `pelage render`: model, --clip, --size, --fps, camera and fur options; the same for every task).
# Frame f's pixels depend only on the inputs and f, so the tasks' frames equal one run's, byte for
# byte; a retried task skips the frames it already finished (--resume).
set -euo pipefail

: "${FIRST:?set FIRST (first frame)}"
: "${LAST:?set LAST (last frame, inclusive)}"
: "${OUT:?set OUT (shared output directory)}"
PELAGE=${PELAGE:-pelage}
PELAGE_ARGS=${PELAGE_ARGS:-}

if [[ -n "${PELAGE_TASK_INDEX:-}" ]]; then
  index=$PELAGE_TASK_INDEX
elif [[ -n "${SLURM_ARRAY_TASK_ID:-}" ]]; then
  index=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-0}))
elif [[ -n "${JOB_COMPLETION_INDEX:-}" ]]; then
  index=$JOB_COMPLETION_INDEX
else
  echo "render-range.sh: no task index (SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or PELAGE_TASK_INDEX)" >&2
  exit 2
fi
count=${PELAGE_TASK_COUNT:-${SLURM_ARRAY_TASK_COUNT:-}}
if [[ -z "$count" || "$count" -lt 1 || "$index" -lt 0 || "$index" -ge "$count" ]]; then
  echo "render-range.sh: task index '$index' of '$count' tasks is not valid (0 <= index < count)" >&2
  exit 2
fi

# Contiguous ranges of ceil(total / count) frames; the last tasks may get fewer, or none.
total=$((LAST - FIRST + 1))
per=$(((total + count - 1) / count))
a=$((FIRST + index * per))
b=$((a + per - 1))
((b > LAST)) && b=$LAST
if ((a > LAST)); then
  echo "task $index/$count: no frames left"
  exit 0
fi
echo "task $index/$count: frames $a..$b of $FIRST..$LAST -> $OUT"
# Worker threads: the CPUs the engine gave this task (0 = all the machine's).
threads=${SLURM_CPUS_PER_TASK:-${PELAGE_THREADS:-0}}
# shellcheck disable=SC2086  # PELAGE_ARGS is a list of words
exec "$PELAGE" --threads "$threads" render $PELAGE_ARGS --frames "$a:$b" --out "$OUT" --resume
